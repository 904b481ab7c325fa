// inertest: the command-line shell over the library. Every command lives in its own file and
// registers itself (command.h). Errors: message on stderr, exit status 2.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fmt/format.h>

#include "command.h"
#include "inertest/core/error.h"
#include "inertest/core/filesystem_error.h"
#include "inertest/version.h"

namespace {

// A command line that does not parse, in the product's error form and status (CLI11's own are
// "FILE: File does not exist: x" and statuses 104-106): help and --version still exit 0.
int refuse_command_line(const CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
  const std::string first = argc > 1 ? argv[1] : "";
  const bool command = !app.get_subcommands([&](const CLI::App* c) { return c->check_name(first); }).empty();
  std::string message = e.what();
  // A first word that is no option and no command: CLI11 says only that a command is required.
  if (!first.empty() && first.front() != '-' && !command) message = fmt::format("unknown command '{}'", first);
  fmt::print(stderr, "inertest: error: {} (see inertest{} --help)\n", message, command ? " " + first : "");
  return 2;
}

// What a command printed must have reached stdout whole: a full disk behind `> results.json` left
// the file empty and the status 0.
int with_stdout_flushed(int status) {
  if (std::fflush(stdout) != 0 || std::ferror(stdout) != 0) {
    fmt::print(stderr, "inertest: error: cannot write the standard output: {}\n", std::strerror(errno));
    return 2;
  }
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"inertest: test data processing for gyroscopes and accelerometers "
               "(GJB 2426A-2004, IEEE Std 952-1997)",
               "inertest"};
  app.set_version_flag("--version", "inertest " + inertest::version());
  app.require_subcommand(1);
  const auto commands = inertest::cli::add_registered_commands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return refuse_command_line(app, e, argc, argv);
  }
  try {
    for (const auto& [subcommand, action] : commands) {
      if (subcommand->parsed()) return with_stdout_flushed(action());
    }
  } catch (const inertest::Error& e) {
    fmt::print(stderr, "inertest: error: {}\n", e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // A path of the user's the system refuses (a read-only share, a file where a directory goes):
    // bad input, said with the path, not an internal error.
    fmt::print(stderr, "inertest: error: {}\n", inertest::error_of(e).what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "inertest: internal error: {}\n", e.what());
    return 3;
  }
  return 1;
}

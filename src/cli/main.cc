// inertest: the command-line shell over the library. Every command lives in its own file and
// registers itself (command.h). Errors: message on stderr, exit status 2.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <fmt/format.h>

#include "command.h"
#include "inertest/core/error.h"
#include "inertest/version.h"

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
    return app.exit(e);
  }
  try {
    for (const auto& [subcommand, action] : commands) {
      if (subcommand->parsed()) return action();
    }
  } catch (const inertest::Error& e) {
    fmt::print(stderr, "inertest: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "inertest: internal error: {}\n", e.what());
    return 3;
  }
  return 1;
}

// inertest: the command-line shell over the library. Every command lives in its own file and
// registers itself (command.h). Errors: message on stderr, exit status 2.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <numeric>
#include <optional>
#include <string>
#include <vector>
#include <fmt/format.h>

#include "command.h"
#include "inertest/core/error.h"
#include "inertest/core/filesystem_error.h"
#include "inertest/version.h"

namespace {

// The name of `names` nearest `word` by edit distance (Levenshtein), when a slip of the keys apart:
// at most 2 edits, and fewer than half the word's characters (an option's "--" counted).
std::optional<std::string> nearest(const std::string& word, const std::vector<std::string>& names) {
  std::optional<std::string> best;
  std::size_t best_distance = std::min<std::size_t>(3, (word.size() + 1) / 2);
  for (const std::string& name : names) {
    std::vector<std::size_t> row(name.size() + 1);
    std::iota(row.begin(), row.end(), std::size_t{0});
    for (std::size_t i = 1; i <= word.size(); ++i) {
      std::size_t diagonal = row[0];
      row[0] = i;
      for (std::size_t j = 1; j <= name.size(); ++j) {
        const std::size_t above = row[j];
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (word[i - 1] == name[j - 1] ? 0 : 1)});
        diagonal = above;
      }
    }
    if (row.back() < best_distance) best_distance = row.back(), best = name;
  }
  return best;
}

// " (did you mean --rate-unit?)" for the first option of the command line that `command` does not
// have and that is near one of its own; "" for none.
std::string option_suggestion(const CLI::App& command, int argc, char** argv) {
  std::vector<std::string> names;
  for (const CLI::Option* option : command.get_options()) {
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
  }
  for (int i = 2; i < argc; ++i) {
    const std::string argument = argv[i];
    if (!argument.starts_with("--")) continue;
    const std::string given = argument.substr(0, argument.find('='));
    if (std::find(names.begin(), names.end(), given) != names.end()) continue;
    if (const auto near = nearest(given, names)) return fmt::format(" ({}: did you mean {}?)", given, *near);
  }
  return "";
}

// A command line that does not parse, in the product's error form and status (CLI11's own are
// "FILE: File does not exist: x" and statuses 104-106): help and --version still exit 0. A mistyped
// command or option is answered with the nearest one.
int refuse_command_line(const CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
  const std::string first = argc > 1 ? argv[1] : "";
  const std::vector<const CLI::App*> matched =
      app.get_subcommands([&](const CLI::App* c) { return c->check_name(first); });
  std::string message = e.what();
  if (!matched.empty()) {
    // The command the options belong to: `archive fleet`'s, not `archive`'s.
    const CLI::App* command = matched.front();
    for (int i = 2; i < argc; ++i) {
      const std::string word = argv[i];
      const auto sub = command->get_subcommands([&](const CLI::App* c) { return c->check_name(word); });
      if (sub.empty()) break;
      command = sub.front();
    }
    message += option_suggestion(*command, argc, argv);
  } else if (!first.empty() && first.front() != '-') {
    // A first word that is no option and no command: CLI11 says only that a command is required.
    std::vector<std::string> commands;
    for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
      commands.push_back(command->get_name());
    }
    const std::optional<std::string> near = nearest(first, commands);
    message = fmt::format("unknown command '{}'{}", first, near ? fmt::format(" (did you mean {}?)", *near) : "");
  }
  fmt::print(stderr, "inertest: error: {} (see inertest{} --help)\n", message, matched.empty() ? "" : " " + first);
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

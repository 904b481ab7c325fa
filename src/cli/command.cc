#include "command.h"

#include <algorithm>
#include <cstdio>
#include <fmt/format.h>
#include <map>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "inertest/core/json_text.h"
#include "procedure_command.h"

namespace inertest::cli {
namespace {

std::map<std::string, CommandSetup>& registry() {
  static std::map<std::string, CommandSetup> commands;
  return commands;
}

}  // namespace

bool register_command(const std::string& name, CommandSetup setup) {
  registry().emplace(name, std::move(setup));
  return true;
}

std::vector<std::pair<CLI::App*, CommandAction>> add_registered_commands(CLI::App& root) {
  std::map<std::string, CommandSetup> commands = registry();
  for (const ProcedureSpec& spec : procedure_specs()) {
    // A spec's command in a group (`misalignment gyro`) is added to the group, made by the first.
    const std::string name = spec.command_path.empty() ? kebab_case(spec.kind)
                                                        : spec.command_path.front() + " " + spec.command_path.back();
    const auto [at, added] = commands.emplace(name, [&spec](CLI::App& app) {
      if (spec.command_path.empty()) return add_procedure_command(app, spec);
      const std::vector<CLI::App*> made =
          app.get_subcommands([&spec](CLI::App* command) { return command->get_name() == spec.command_path.front(); });
      CLI::App* group = made.empty() ? app.add_subcommand(spec.command_path.front())->require_subcommand(1) : made.front();
      if (!spec.command_group_doc.empty()) group->description(spec.command_group_doc);
      return add_procedure_command(*group, spec);
    });
    if (!added) throw Error("two commands named '" + at->first + "'");
  }
  std::vector<std::pair<CLI::App*, CommandAction>> added;
  for (const auto& [name, setup] : commands) {
    CommandAction action = setup(root);
    CLI::App* command = &root;
    for (std::size_t begin = 0; begin < name.size();) {
      const std::size_t end = std::min(name.find(' ', begin), name.size());
      command = command->get_subcommand(name.substr(begin, end - begin));
      begin = end + 1;
    }
    added.emplace_back(command, std::move(action));
  }
  return added;
}

void print_result(const nlohmann::json& json, const std::string& report, bool as_json) {
  const std::string text = as_json ? json_text(json, 2) + "\n" : report;
  std::fwrite(text.data(), 1, text.size(), stdout);
  std::fflush(stdout);
}

ProgressCallback terminal_progress() {
  if (::isatty(STDERR_FILENO) == 0) return {};
  return [](std::string_view stage, double fraction) {
    fmt::print(stderr, "\r{:<40} {:5.1f} %{}", stage, 100.0 * fraction, fraction >= 1.0 ? "\n" : "");
    std::fflush(stderr);
  };
}

}  // namespace inertest::cli

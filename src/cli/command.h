// Subcommands register themselves here (one file per command, git style), so adding a command
// touches no shared file. Each command's setup adds its CLI11 subcommand and returns the action
// to run once the arguments are parsed.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/core/progress.h"

namespace inertest::cli {

using CommandAction = std::function<int()>;
using CommandSetup = std::function<CommandAction(CLI::App& root)>;

// Registers a command; call from a namespace-scope object's initialiser.
bool register_command(const std::string& name, CommandSetup setup);

// Adds every registered command to root, sorted by name; returns (subcommand, action) pairs.
std::vector<std::pair<CLI::App*, CommandAction>> add_registered_commands(CLI::App& root);

// Prints a result: exactly one JSON object on stdout with --json, else the readable report.
void print_result(const nlohmann::json& json, const std::string& report, bool as_json);

// Progress on stderr when stderr is a terminal; nothing otherwise (never on stdout).
ProgressCallback terminal_progress();

}  // namespace inertest::cli

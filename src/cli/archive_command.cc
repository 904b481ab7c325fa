// inertest archive add|list|history|...: the results archive (include/inertest/archive/archive.h).
#include "archive_command.h"

#include <map>

namespace inertest::cli {
namespace {

std::map<std::string, CommandSetup>& archive_registry() {
  static std::map<std::string, CommandSetup> commands;
  return commands;
}

CommandAction setup(CLI::App& root) {
  CLI::App* command = root.add_subcommand(
      "archive",
      "The results archive: campaigns' results.json stored in a database (SQLite file, the default\n"
      "~/.local/share/inertest/archive.sqlite or $INERTEST_DB, or a postgresql:// URL), queried\n"
      "across days (one instrument's history) and across a fleet.");
  command->require_subcommand(1);
  auto actions = std::make_shared<std::vector<std::pair<CLI::App*, CommandAction>>>();
  for (const auto& [name, archive_setup] : archive_registry()) {
    CommandAction action = archive_setup(*command);
    actions->emplace_back(command->get_subcommand(name), std::move(action));
  }
  return [actions] {
    for (const auto& [subcommand, action] : *actions) {
      if (subcommand->parsed()) return action();
    }
    return 1;
  };
}

const bool registered = register_command("archive", setup);

}  // namespace

bool register_archive_command(const std::string& name, CommandSetup setup) {
  archive_registry().emplace(name, std::move(setup));
  return true;
}

void add_db_option(CLI::App& command, std::string& db) {
  command.add_option("--db", db,
                     "the archive: a file path (SQLite) or a postgresql:// URL; default $INERTEST_DB, else "
                     "~/.local/share/inertest/archive.sqlite");
}

std::string archive_location_option(const std::string& db) {
  return db.empty() ? archive::default_archive_location() : db;
}

std::unique_ptr<archive::Archive> open_archive_option(const std::string& db, archive::ArchiveOpening opening) {
  return archive::open_archive(archive_location_option(db), opening);
}

}  // namespace inertest::cli

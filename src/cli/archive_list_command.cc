// inertest archive list [--instrument ID] [--db DB] [--json]
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "archive_command.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string instrument;
  std::string db;
  bool json = false;
};

CommandAction setup(CLI::App& archive) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = archive.add_subcommand("list", "List the archived campaigns, oldest test first.");
  command->add_option("--instrument", arguments->instrument, "only this instrument's campaigns");
  add_db_option(*command, arguments->db);
  command->add_flag("--json", arguments->json,
                    "print {\"campaigns\": [{\"id\", \"instrument\", \"title\", \"tested_on\", \"processed_at\", "
                    "\"verdict\", \"superseded_by\"}]}");
  return [arguments] {
    const auto store = open_archive_option(arguments->db);
    const auto entries =
        store->list(arguments->instrument.empty() ? std::nullopt : std::optional<std::string>(arguments->instrument));
    std::string report = fmt::format("{:<16}  {:<16}  {:<10}  {:<20}  {:<7}  {}\n", "id", "instrument", "tested on",
                                     "processed at", "verdict", "title");
    for (const auto& e : entries) {
      report += fmt::format("{:<16}  {:<16}  {:<10}  {:<20}  {:<7}  {}{}\n", e.id, e.instrument, e.tested_on,
                            e.processed_at, e.verdict, e.title,
                            e.superseded_by.empty() ? "" : fmt::format("  (figures superseded by {})", fmt::join(e.superseded_by, ", ")));
    }
    print_result(archive::campaign_list_json(entries), report, arguments->json);
    return 0;
  };
}

const bool registered = register_archive_command("list", setup);

}  // namespace
}  // namespace inertest::cli

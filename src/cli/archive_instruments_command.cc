// inertest archive instruments [--db DB] [--json]
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "archive_command.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string db;
  bool json = false;
};

CommandAction setup(CLI::App& archive) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = archive.add_subcommand(
      "instruments", "List the archived instruments, each with its number of campaigns and its latest verdict.");
  add_db_option(*command, arguments->db);
  command->add_flag("--json", arguments->json,
                    "print {\"instruments\": [{\"instrument\", \"campaigns\", \"latest\": {\"id\", \"instrument\", "
                    "\"title\", \"tested_on\", \"processed_at\", \"verdict\"}}]}");
  return [arguments] {
    const auto store = open_archive_option(arguments->db);
    const nlohmann::json json = archive::instrument_list_json(store->list(std::nullopt));
    std::string report = fmt::format("{:<16}  {:>9}  {:<10}  {:<7}  {}\n", "instrument", "campaigns", "latest", "verdict",
                                     "campaign");
    for (const auto& i : json["instruments"]) {
      const auto& latest = i["latest"];
      report += fmt::format("{:<16}  {:>9}  {:<10}  {:<7}  {}\n", i["instrument"].get<std::string>(),
                            i["campaigns"].get<std::size_t>(), latest["tested_on"].get<std::string>(),
                            latest["verdict"].get<std::string>(), latest["id"].get<std::string>());
    }
    print_result(json, report, arguments->json);
    return 0;
  };
}

const bool registered = register_archive_command("instruments", setup);

}  // namespace
}  // namespace inertest::cli

// inertest archive add RESULTS.json... [--db DB] [--json]
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "archive_command.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::vector<std::string> files;
  std::string db;
  bool json = false;
};

CommandAction setup(CLI::App& archive) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = archive.add_subcommand(
      "add",
      "Add campaigns' results.json to the archive, all in one transaction. A campaign already there\n"
      "(the same content, whatever its processing time) is recognised and stored once; a later\n"
      "processing of the same records (a changed limit, a newer inertest) supersedes the earlier's\n"
      "figures step by step, which stay stored and listed. All files are\n"
      "read and checked before any is added: a malformed one adds nothing, nor does a failure of the\n"
      "database part-way.");
  command->add_option("RESULTS", arguments->files, "results.json of inertest run")->required();
  add_db_option(*command, arguments->db);
  command->add_flag("--json", arguments->json,
                    "print {\"added\": [{\"id\", \"instrument\", \"file\", \"added\", \"supersedes\", \"superseded_by\"}]} on "
                    "stdout");
  return [arguments] {
    std::vector<std::pair<nlohmann::json, std::string>> files;
    for (const auto& file : arguments->files) {
      files.emplace_back(archive::read_results_file(file), file);
      archive::check_results(files.back().first, file);  // before the archive is opened (or created)
    }
    const auto store = open_archive_option(arguments->db, archive::ArchiveOpening::create);
    const std::vector<archive::AddOutcome> outcomes = store->add_all(files);
    nlohmann::json added = nlohmann::json::array();
    std::string report;
    for (std::size_t i = 0; i < outcomes.size(); ++i) {
      const archive::AddOutcome& outcome = outcomes[i];
      added.push_back(outcome.to_json(arguments->files[i]));
      report += outcome.to_text(arguments->files[i]) + "\n";
    }
    print_result({{"added", added}}, report, arguments->json);
    return 0;
  };
}

const bool registered = register_archive_command("add", setup);

}  // namespace
}  // namespace inertest::cli

// inertest run PLAN.toml --out DIR [--archive [DB]]
#include <filesystem>
#include <optional>

#include <fmt/format.h>

#include "archive_command.h"
#include "command.h"
#include "inertest/campaign/campaign.h"
#include "inertest/report/report.h"

namespace inertest::cli {
namespace {

// What a run makes to hold a new archive file: the file, or the topmost of its directories that is
// not there yet; nothing for an archive that exists or a server's. A run that fails removes it (a bad
// data file left a new, empty archive behind).
std::optional<std::filesystem::path> made_for_archive(const std::string& location) {
  if (archive::is_server_location(location)) return std::nullopt;
  std::filesystem::path path = std::filesystem::absolute(location);
  if (std::filesystem::exists(path)) return std::nullopt;
  while (path.has_parent_path() && path.parent_path() != path && !std::filesystem::exists(path.parent_path())) {
    path = path.parent_path();
  }
  return path;
}

struct Arguments {
  std::string plan;
  std::string out;
  std::string lang = "en";
  std::string archive;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "run",
      "Run a test plan (TOML): validate it whole (errors name the plan's file and line; nothing runs),\n"
      "then run every procedure it names, check its specification limits, and write DIR/results.json\n"
      "and the test report DIR/report.html.");
  command->add_option("PLAN", arguments->plan, "test plan, TOML")->required();
  command->add_option("--out", arguments->out, "output directory")->required();
  command->add_option("--lang", arguments->lang, "language of the report: en or zh (GJB terms)")
      ->check(CLI::IsMember({"en", "zh"}));
  command->add_flag("--json", arguments->json, "print results.json on stdout as well");
  CLI::Option* archive_option =
      command->add_option("--archive", arguments->archive,
                          "add the results to the archive DB (a file or a postgresql:// URL; without DB, "
                          "$INERTEST_DB, else ~/.local/share/inertest/archive.sqlite)")
          ->expected(0, 1);
  return [arguments, archive_option] {
    // The archive is opened first: one that cannot be opened stops the run before anything is written.
    // A plan that would be refused is refused before that (a mistyped key made a new, empty archive).
    const bool archiving = archive_option->count() > 0;
    if (archiving) validate_plan(arguments->plan);
    const std::optional<std::filesystem::path> made =
        archiving ? made_for_archive(archive_location_option(arguments->archive)) : std::nullopt;
    auto store = archiving ? open_archive_option(arguments->archive, archive::ArchiveOpening::create) : nullptr;
    const report::ReportOptions report_options{report::parse_language(arguments->lang), report::current_date()};
    CampaignOptions options;
    options.progress = terminal_progress();
    options.report_page = [&report_options](const nlohmann::json& results) {
      return report::render_report(results, report_options);
    };
    CampaignSummary summary;
    try {
      summary = run_campaign(arguments->plan, arguments->out, options);
    } catch (...) {
      store.reset();
      if (made) std::filesystem::remove_all(*made);
      throw;
    }
    if (store) {
      const auto outcome = store->add(summary.results, summary.written_files.front());
      fmt::print(stderr, "{} the archive as campaign {}{}\n", outcome.added ? "added to" : "already in", outcome.id,
                 outcome.supersedes.empty() ? ""
                                            : fmt::format(", superseding {} (an earlier processing of the same records)",
                                                          fmt::join(outcome.supersedes, ", ")));
    }
    print_result(summary.results, report::render_text_report(summary.results, report_options), arguments->json);
    if (!arguments->json) {
      fmt::print(stderr, "results written to {}\nreport written to {}\n", summary.written_files.front(),
                 (std::filesystem::path(summary.written_files.front()).parent_path() / "report.html").string());
    }
    for (const auto& file : summary.removed_files) {
      fmt::print(stderr, "removed {}: the last run wrote it, this plan does not\n", file);
    }
    return 0;
  };
}

const bool registered = register_command("run", setup);

}  // namespace
}  // namespace inertest::cli

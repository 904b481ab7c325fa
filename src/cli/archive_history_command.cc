// inertest archive history ID --figure PROCEDURE/FIGURE [--db DB] [--json]
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "archive_command.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string instrument;
  std::string figure;
  std::string db;
  bool json = false;
};

CommandAction setup(CLI::App& archive) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = archive.add_subcommand(
      "history", "One figure of one instrument across its archived campaigns, oldest test first.");
  command->add_option("ID", arguments->instrument, "instrument id (results.json instrument.id)")->required();
  command->add_option("--figure", arguments->figure,
                      "PROCEDURE/FIGURE as named in results.json, e.g. scale_factor/scale_factor")
      ->required();
  add_db_option(*command, arguments->db);
  command->add_flag("--json", arguments->json,
                    "print {\"instrument\", \"figure\", \"unit\", \"points\": [{\"tested_on\", \"value\", "
                    "\"uncertainty\", \"campaign\"}] (value null: not measured), \"lower_limit\", \"upper_limit\", \"limit_on_magnitude\"} (a plan's "
                    "max alone bounds |value|: lower_limit is -max, limit_on_magnitude true)");
  return [arguments] {
    const auto store = open_archive_option(arguments->db);
    const archive::FigureHistory history = store->history(arguments->instrument, arguments->figure);
    std::string report = fmt::format("{} {} ({})\n", history.instrument, history.figure, history.unit);
    if (history.lower_limit || history.upper_limit) {  // the plans' limits, in the figure's unit
      const auto limit = [](const std::optional<double>& v) { return v ? fmt::format("{:.10g}", *v) : "-"; };
      report += history.limit_on_magnitude
                    ? fmt::format("  limits: |value| <= {}\n", limit(history.upper_limit))
                    : fmt::format("  limits: min {}, max {}\n", limit(history.lower_limit), limit(history.upper_limit));
    }
    for (const auto& p : history.points) {
      report += fmt::format("  {}  {}{}  {}\n", p.tested_on, p.value ? fmt::format("{:.10g}", *p.value) : "not measured",
                            p.value && p.uncertainty ? fmt::format(" ± {:.3g}", *p.uncertainty) : std::string(), p.campaign);
    }
    print_result(history.to_json(), report, arguments->json);
    return 0;
  };
}

const bool registered = register_archive_command("history", setup);

}  // namespace
}  // namespace inertest::cli

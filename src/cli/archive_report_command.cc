// inertest archive report --out DIR [--figure PROCEDURE/FIGURE]... [--lang en|zh] [--db DB]
#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "archive_command.h"
#include "inertest/report/archive_pages.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string out;
  std::vector<std::string> figures;
  std::string lang = "en";
  std::string db;
};

CommandAction setup(CLI::App& archive) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = archive.add_subcommand(
      "report",
      "Write the archive's report pages, all of them or none: DIR/fleet.html (a control chart and the\n"
      "capability of each figure) and DIR/history-<ID>.html for every instrument (trend plots with\n"
      "uncertainty bars and the specification limits; in the name, every byte of the id but letters,\n"
      "digits, '-', '.' and '_' percent-encoded). Figures: those given, else every figure a plan set\n"
      "limits on.");
  command->add_option("--out", arguments->out, "output directory")->required();
  command->add_option("--figure", arguments->figures, "PROCEDURE/FIGURE (repeatable)");
  command->add_option("--lang", arguments->lang, "language: en or zh (GJB terms)")->check(CLI::IsMember({"en", "zh"}));
  add_db_option(*command, arguments->db);
  return [arguments] {
    const auto store = open_archive_option(arguments->db);
    const std::vector<std::string> figures = arguments->figures.empty() ? store->figures(true) : arguments->figures;
    if (figures.empty()) throw Error("no figure has specification limits in the archive: name them with --figure");
    // An unknown name is an error, not an empty page.
    const std::vector<std::string> archived = store->figures(false);
    for (const auto& figure : figures) {
      if (!std::binary_search(archived.begin(), archived.end(), figure)) throw Error("figure '" + figure + "' is not archived");
    }
    const auto written = report::write_archive_pages(archive::report_data(*store, figures), arguments->out,
                                                     {report::parse_language(arguments->lang), report::current_date()});
    for (const auto& path : written) fmt::print(stderr, "written: {}\n", path);
    return 0;
  };
}

const bool registered = register_archive_command("report", setup);

}  // namespace
}  // namespace inertest::cli

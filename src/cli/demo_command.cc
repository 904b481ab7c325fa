// inertest demo --out DIR [--fleet]
#include <cstdio>
#include <fmt/format.h>

#include "command.h"
#include "inertest/demo/demo.h"
#include "inertest/demo/fleet_demo.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string out;
  std::string plan;
  std::string lang = "en";
  bool json = false;
  bool fleet = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "demo",
      "Simulate a complete test campaign of a navigation-grade FOG in the virtual lab, process it\n"
      "(inertest run), and check every measured figure against the simulated truth. Writes\n"
      "DIR/lab/ (records, plan, truth.json), DIR/results.json (with truth_check), DIR/report.txt and\n"
      "the test report DIR/report.html.\n"
      "Exit status 1 when a measured figure falls outside its tolerance.");
  command->add_option("--out", arguments->out, "output directory")->required();
  command->add_option("--plan", arguments->plan, "simulation plan instead of the built-in one");
  command->add_option("--lang", arguments->lang, "language of report.html: en or zh (GJB terms)")
      ->check(CLI::IsMember({"en", "zh"}));
  command->add_flag("--json", arguments->json, "print results.json on stdout");
  command->add_flag("--fleet", arguments->fleet,
                    "instead: a production batch of 12 simulated gyros (3 out of specification), each tested on 3\n"
                    "days, archived into DIR/archive.sqlite; writes DIR/fleet.html and DIR/history-<ID>.html");
  return [arguments] {
    if (arguments->fleet) {
      FleetDemoOptions fleet_options;
      fleet_options.report = {report::parse_language(arguments->lang), report::current_date()};
      fleet_options.progress = terminal_progress();
      const FleetDemoSummary summary = run_fleet_demo(arguments->out, fleet_options);
      print_result(summary.fleet, summary.report(), arguments->json);
      return 0;
    }
    DemoOptions options;
    options.simulation_plan = arguments->plan;
    options.report = {report::parse_language(arguments->lang), report::current_date()};
    // One line per stage and per tenth of a long stage: a log, not a flood (the long Allan record
    // reports hundreds of steps).
    options.progress = [last_stage = std::string(), last_tenth = -1](std::string_view stage,
                                                                     double fraction) mutable {
      const int tenth = static_cast<int>(10.0 * fraction);
      if (stage == last_stage && tenth == last_tenth) return;
      last_stage = std::string(stage);
      last_tenth = tenth;
      fmt::print(stderr, "[demo] {:<40} {:5.1f} %\n", stage, 100.0 * fraction);
      std::fflush(stderr);
    };
    const DemoSummary summary = run_demo(arguments->out, options);
    print_result(summary.results, summary.report, arguments->json);
    fmt::print(stderr, "report: {}\nhtml report: {}\nresults: {}\n", summary.report_path, summary.html_report_path,
               summary.results_path);
    return summary.all_within ? 0 : 1;
  };
}

const bool registered = register_command("demo", setup);

}  // namespace
}  // namespace inertest::cli

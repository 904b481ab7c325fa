// inertest run PLAN.toml --out DIR
#include <fmt/format.h>

#include "command.h"
#include "inertest/campaign/campaign.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string plan;
  std::string out;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "run",
      "Run a test plan (TOML): validate it whole (errors name the plan's file and line; nothing runs),\n"
      "then run every procedure it names, check its specification limits, and write DIR/results.json.");
  command->add_option("PLAN", arguments->plan, "test plan, TOML")->required();
  command->add_option("--out", arguments->out, "output directory")->required();
  command->add_flag("--json", arguments->json, "print results.json on stdout as well");
  return [arguments] {
    CampaignOptions options;
    options.progress = terminal_progress();
    const CampaignSummary summary = run_campaign(arguments->plan, arguments->out, options);
    print_result(summary.results, summary.report(), arguments->json);
    if (!arguments->json) fmt::print(stderr, "results written to {}\n", summary.written_files.front());
    return 0;
  };
}

const bool registered = register_command("run", setup);

}  // namespace
}  // namespace inertest::cli

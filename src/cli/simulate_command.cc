// inertest simulate PLAN.toml --out DIR [--seed N] [--instrument ID] [--date YYYY-MM-DD]
#include <cstdint>
#include <fmt/format.h>

#include "command.h"
#include "inertest/sim/simulation.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string plan;
  std::string out;
  std::uint64_t seed = 0;
  std::string instrument;
  std::string date;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "simulate",
      "Virtual lab: simulate the gyro and the rigs a simulation plan (TOML) names, and write into DIR\n"
      "the records of every test, plan.toml (the test plan that processes them: inertest run) and\n"
      "truth.json (the true parameters and the tolerance of each measured figure). Same seed, same files.\n"
      "A [[test]] may carry [test.limits], figure = { min, max, unit }: the specification limits of its\n"
      "step in plan.toml ([procedure.limits]), which inertest run checks (a PASS/FAIL verdict per limit).");
  command->add_option("PLAN", arguments->plan, "simulation plan, TOML")->required();
  command->add_option("--out", arguments->out, "output directory")->required();
  CLI::Option* seed = command->add_option("--seed", arguments->seed, "seed instead of the plan's (one instrument of a batch)");
  command->add_option("--instrument", arguments->instrument, "the gyro's id instead of the plan's");
  command->add_option("--date", arguments->date, "test date written into the processing plan, YYYY-MM-DD");
  return [arguments, seed] {
    sim::SimulationOptions options;
    options.progress = terminal_progress();
    if (seed->count() > 0) options.seed = arguments->seed;
    options.instrument_id = arguments->instrument;
    options.date = arguments->date;
    const sim::SimulationSummary summary = sim::simulate(arguments->plan, arguments->out, options);
    fmt::print(stderr, "{} files written; processing plan: {}\n", summary.written_files.size(), summary.plan_path);
    return 0;
  };
}

const bool registered = register_command("simulate", setup);

}  // namespace
}  // namespace inertest::cli

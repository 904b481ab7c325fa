// inertest simulate PLAN.toml --out DIR [--seed N] [--instrument ID] [--date YYYY-MM-DD]
#include <cmath>
#include <cstdint>
#include <fmt/format.h>

#include "command.h"
#include "inertest/sim/simulation.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string plan;
  std::string out;
  double seed = 0.0;  // checked as the plan's seed is: a whole number from 0 to 2^53
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
  CLI::Option* seed =
      command
          ->add_option(
              "--seed", arguments->seed,
              "seed of the noise instead of the plan's (another run of the same gyro: its parameters are the plan's)")
          ->type_name("UINT");
  CLI::Option* instrument = command->add_option("--instrument", arguments->instrument, "the gyro's id instead of the plan's");
  command->add_option("--date", arguments->date, "test date written into the processing plan, YYYY-MM-DD");
  return [arguments, seed, instrument] {
    sim::SimulationOptions options;
    options.progress = terminal_progress();
    if (seed->count() > 0) {
      // -1 and 1e23 became 18446744073709551615, one lab for both; the plan's seed is held to this.
      const double given = arguments->seed;
      if (!(given >= 0.0 && given == std::floor(given) && given <= 9.007199254740992e15)) {
        throw Error(fmt::format("--seed {}: must be a whole number from 0 to 2^53", given));
      }
      options.seed = static_cast<std::uint64_t>(given);
    }
    if (instrument->count() > 0 && arguments->instrument.empty()) throw Error("--instrument is empty: give the gyro's id");
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

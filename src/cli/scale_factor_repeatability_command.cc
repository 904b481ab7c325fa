// inertest scale-factor-repeatability POINTS1.csv ... POINTSQ.csv [--json]
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/scale_factor_repeatability.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::vector<std::string> files;
  ScaleFactorRepeatabilityOptions options;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "scale-factor-repeatability",
      "Scale factor repeatability Kr (GJB 2426A-2004 5.8.4, eq. 12) over Q runs of the scale-factor test.\n"
      "Each FILE is one run's test points, header 'rate,output', as for 'inertest scale-factor'.\n"
      "GJB 2426A 5.8.4.3 asks for Q >= 6 runs: fewer is an error unless --minimum-runs is lowered\n"
      "(to no less than 2), and the result then carries a warning.\n"
      "Outputs: scale_factor_repeatability (ppm), mean_scale_factor, run_scale_factors.");
  command->add_option("FILE", arguments->files, "one CSV of test points per run")->required()->check(CLI::ExistingFile);
  command->add_option("--minimum-runs", arguments->options.minimum_runs, "fewest runs accepted")->capture_default_str();
  command->add_option("--rate-unit", arguments->options.scale_factor.rate_unit, "unit of the rates")
      ->capture_default_str();
  command->add_option("--output-unit", arguments->options.scale_factor.output_unit, "instrument output unit")
      ->capture_default_str();
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    std::vector<std::vector<ScaleFactorPoint>> runs;
    for (const auto& file : arguments->files) runs.push_back(read_scale_factor_points(file));
    const auto result = scale_factor_repeatability(runs, arguments->options);
    print_result(result.to_json(), result.report(), arguments->json);
    return 0;
  };
}

const bool registered = register_command("scale-factor-repeatability", setup);

}  // namespace
}  // namespace inertest::cli

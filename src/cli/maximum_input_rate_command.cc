// inertest maximum-input-rate POINTS.csv --nonlinearity-limit PPM [--json]
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/maximum_input_rate.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string points_file;
  MaximumInputRateOptions options;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "maximum-input-rate",
      "Maximum input rate (GJB 2426A-2004 5.9): the largest tested rate R such that the scale-factor\n"
      "nonlinearity (eqs. 1-9) over the points with |rate| <= R meets --nonlinearity-limit, for that R\n"
      "and every smaller one. POINTS has the header 'rate,output', as for 'inertest scale-factor',\n"
      "tested beyond the expected maximum.\n"
      "Outputs: maximum_input_rate (rate unit), nonlinearity (ppm), scale_factor, ranges (Kn per R).");
  command->add_option("POINTS", arguments->points_file, "CSV of test points (rate,output)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--nonlinearity-limit", arguments->options.nonlinearity_limit_ppm,
                      "the nonlinearity requirement, ppm")
      ->required();
  command->add_option("--rate-unit", arguments->options.scale_factor.rate_unit, "unit of the rates")
      ->capture_default_str();
  command->add_option("--output-unit", arguments->options.scale_factor.output_unit, "instrument output unit")
      ->capture_default_str();
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    const auto points = read_scale_factor_points(arguments->points_file);
    const auto result = maximum_input_rate(points, arguments->options);
    print_result(result.to_json(), result.report(), arguments->json);
    return 0;
  };
}

const bool registered = register_command("maximum-input-rate", setup);

}  // namespace
}  // namespace inertest::cli

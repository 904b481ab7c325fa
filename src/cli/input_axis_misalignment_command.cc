// inertest input-axis-misalignment POSITIONS.csv --scale-factor K --rate OMEGA [--json]
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/input_axis_misalignment.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string positions_file;
  InputAxisMisalignmentOptions options;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "input-axis-misalignment",
      "Input-axis misalignment alpha (GJB 2426A-2004 5.15, eqs. 47-50), IRA perpendicular to the table\n"
      "axis. POSITIONS has the header 'position,output_positive,output_negative': positions 1, 2 (ox,\n"
      "then oy along the table axis) and optionally 3, 4 (the same turned 180 deg about IRA), each with\n"
      "the mean output over whole turns at +rate and -rate.\n"
      "delta_j = (F(j+) - F(j-))/(2 K rate), K in output per input rate; two positions:\n"
      "alpha = asin(sqrt(delta1^2 + delta2^2)); four: the mounting error cancels,\n"
      "alpha = asin(sqrt(((delta1 - delta3)/2)^2 + ((delta2 - delta4)/2)^2)).\n"
      "Outputs: misalignment (arcsec), misalignment_deg, deltas (arcsec); with four positions also\n"
      "misalignment_about_ox/oy, mounting_error and misalignment_eq50_as_printed (arcsec).");
  command->add_option("POSITIONS", arguments->positions_file, "CSV position,output_positive,output_negative")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--scale-factor", arguments->options.scale_factor, "K, output unit per rate unit")->required();
  command->add_option("--rate", arguments->options.rate, "table rate magnitude, rate unit")->required();
  command->add_option("--rate-unit", arguments->options.rate_unit, "unit of --rate and of K's denominator")
      ->capture_default_str();
  command->add_option("--output-unit", arguments->options.output_unit, "instrument output unit")->capture_default_str();
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    const auto positions = read_misalignment_positions(arguments->positions_file);
    const auto result = input_axis_misalignment(positions, arguments->options);
    print_result(result.to_json(), result.report(), arguments->json);
    return 0;
  };
}

const bool registered = register_command("input-axis-misalignment", setup);

}  // namespace
}  // namespace inertest::cli

// inertest scale-factor-temperature RUNS.csv [--reference-temperature DEGC] [--json]
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/scale_factor_temperature_sensitivity.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string runs_file;
  std::optional<double> reference_temperature;
  ScaleFactorTemperatureOptions options;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "scale-factor-temperature",
      "Scale factor temperature sensitivity Kt (GJB 2426A-2004 5.8.5, eq. 13):\n"
      "Kt = max over the test temperatures Ti of |(Ki - Km)/(Km (Ti - Tm))|, in ppm/degC.\n"
      "RUNS is a CSV with the header 'temperature_degC,file': one scale-factor test per temperature\n"
      "(each file has the header 'rate,output', paths relative to RUNS). The room-temperature run\n"
      "Tm is the first row, or the row at --reference-temperature.\n"
      "Outputs: scale_factor_temperature_sensitivity (ppm/degC), reference_scale_factor,\n"
      "reference_temperature, worst_temperature, test_temperatures (K and sensitivity at each).");
  command->add_option("RUNS", arguments->runs_file, "CSV listing temperature_degC,file")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--reference-temperature", arguments->reference_temperature, "room temperature Tm, degC");
  command->add_option("--rate-unit", arguments->options.scale_factor.rate_unit, "unit of the rates")
      ->capture_default_str();
  command->add_option("--output-unit", arguments->options.scale_factor.output_unit, "instrument output unit")
      ->capture_default_str();
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    std::vector<TemperatureRun> runs;
    for (const auto& row : read_file_listing(arguments->runs_file, "temperature_degC")) {
      runs.push_back({row.key, read_scale_factor_points(row.path)});
    }
    arguments->options.reference_temperature_degC = arguments->reference_temperature;
    const auto result = scale_factor_temperature_sensitivity(runs, arguments->options);
    print_result(result.to_json(), result.report(), arguments->json);
    return 0;
  };
}

const bool registered = register_command("scale-factor-temperature", setup);

}  // namespace
}  // namespace inertest::cli

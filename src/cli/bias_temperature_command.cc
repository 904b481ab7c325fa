// inertest bias-temperature --run T:FILE --run T:FILE ... --scale-factor K [--json]
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/core/error.h"
#include "inertest/procedures/bias.h"
#include "inertest/procedures/bias_temperature_sensitivity.h"
#include "record_options.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::vector<std::string> runs;
  OutputRecordSource source;
  BiasOptions options;
  std::optional<double> room_temperature;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "bias-temperature",
      "Bias temperature sensitivity (GJB 2426A-2004 5.12.4, eq. 22): max |B0i - B0m| / |Ti - Tm| over\n"
      "the runs, B0m the bias at room temperature Tm (the first --run, or the run at --room-temperature).\n"
      "Each --run is TEMPERATURE_DEGC:FILE, FILE one run's output record (one column, or --column; or\n"
      "binary with --format); bias = mean output / K in deg/h (eq. 19).\n"
      "JSON: bias_temperature_sensitivity (deg/h/degC), room_temperature, room_temperature_bias, runs.");
  command->add_option("--run", arguments->runs, "TEMPERATURE_DEGC:FILE, once per temperature")->required();
  command->add_option("--room-temperature", arguments->room_temperature, "the room temperature Tm, degC");
  command->add_option("--scale-factor", arguments->options.scale_factor, "K, output units per deg/s");
  command->add_flag("--input-deg-h", arguments->options.input_in_deg_h, "the records hold rate in deg/h already");
  add_record_options(*command, arguments->source);
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    std::vector<TemperatureRunBias> runs;
    for (const auto& text : arguments->runs) {
      auto [temperature, file] = parse_number_and_file(text, "--run", "25:run_25C.txt");
      OutputRecordSource source = arguments->source;
      source.path = file;
      runs.push_back({temperature, bias_deg_h(read_output_record(source), arguments->options)});
    }
    const auto result = bias_temperature_sensitivity(runs, {arguments->room_temperature});
    print_result(result.to_json(), result.report(), arguments->json);
    return 0;
  };
}

const bool registered = register_command("bias-temperature", setup);

}  // namespace
}  // namespace inertest::cli

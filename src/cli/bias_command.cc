// inertest bias FILE --rate HZ --scale-factor K [--smoothing 1,10,100] [--json]
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/procedures/bias.h"
#include "record_options.h"

namespace inertest::cli {
namespace {

struct Arguments {
  OutputRecordSource source;
  BiasOptions options;
  AxisOrientation axis;
  bool remove_earth_rate = false;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "bias",
      "Bias (eq. 19), bias stability (eq. 20) and random walk coefficient by the normalisation method\n"
      "(eqs. 23-24) from one record of the gyro at rest (GJB 2426A-2004 5.12.1, 5.12.2, 5.12.5.4.1).\n"
      "FILE holds the instrument output, one sample (the mean output rate) per sampling interval: a text\n"
      "record (one column, or --column NAME|INDEX) or a binary record (--format f64|f32|...). K is in\n"
      "output units per deg/s; bias = mean output / K in deg/h. Bias stability: standard deviation (n-1)\n"
      "of the means of consecutive whole windows of each smoothing time, in deg/h. Random walk coefficient in\n"
      "deg/sqrt(h) = Bs(1 s)[deg/h] / 60. Earth rate is not removed unless --remove-earth-rate.\n"
      "A smoothing time the record cannot support (longer than half of it, not whole samples) and a random\n"
      "walk coefficient from under 2 s or below 1 Hz are left out with a warning; the bias is always given.\n"
      "JSON: bias, bias_stability [{smoothing_s, value, unit}], random_walk_coefficient,\n"
      "noise_equivalent_rate, normalised_stability_curve, warnings.");
  command->add_option("FILE", arguments->source.path, "instrument output record")->required()->check(CLI::ExistingFile);
  command->add_option("--rate", arguments->options.sample_rate_hz, "sample rate, Hz")->required();
  command->add_option("--scale-factor", arguments->options.scale_factor, "K, output units per deg/s");
  command->add_flag("--input-deg-h", arguments->options.input_in_deg_h,
                    "the record holds rate in deg/h already (no --scale-factor)");
  command->add_option("--smoothing", arguments->options.smoothing_s, "smoothing times for the bias stability, s")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--output-unit", arguments->options.output_unit, "instrument output unit, for the report")
      ->capture_default_str();
  add_record_options(*command, arguments->source);
  command->add_flag("--remove-earth-rate", arguments->remove_earth_rate,
                    "subtract the Earth rate along the IRA (from --latitude, --heading, --elevation) from the bias");
  add_axis_options(*command, arguments->axis);
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    BiasOptions options = arguments->options;
    if (arguments->remove_earth_rate) options.remove_earth_rate = arguments->axis;
    options.validate();
    const std::vector<double> output = read_output_record(arguments->source, 2);
    const BiasResult result = bias(output, options);
    print_result(result.to_json(), result.report(), arguments->json);
    return 0;
  };
}

const bool registered = register_command("bias", setup);

}  // namespace
}  // namespace inertest::cli

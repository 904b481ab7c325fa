// inertest turn-on-time --run RATE:FILE ... --scale-factor K --zero F0 [--rate-band X] [--rest-band B]
// inertest warm-up-time (the same, reported as warm-up time, GJB 2426A 5.6)
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/procedures/turn_on_time.h"
#include "record_options.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::vector<std::string> runs;
  OutputRecordSource source;
  std::optional<double> sample_rate_hz;
  std::string time_column;
  TurnOnTimeOptions options;
  AxisOrientation axis;
  bool remove_earth_rate = false;
  bool json = false;
};

CommandSetup make_setup(bool warm_up) {
  return [warm_up](CLI::App& root) -> CommandAction {
    auto arguments = std::make_shared<Arguments>();
    arguments->options.warm_up = warm_up;
    const std::string name = warm_up ? "warm-up-time" : "turn-on-time";
    CLI::App* command = root.add_subcommand(
        name,
        std::string(warm_up ? "Warm-up time (GJB 2426A-2004 5.6, computed as 5.5.4)"
                            : "Turn-on time (GJB 2426A-2004 5.5.4)") +
            ": from records that start at power-on, the time until the\n"
            "indicated rate (F - F0)/K - Earth rate stays within the band to the end of the record; the\n"
            "largest over the runs. Each --run is INPUT_RATE_DEG_S:FILE (0 for a run at rest).\n"
            "Record layout: a text record with a time column (s since power-on; --time-column, default the\n"
            "first) and an output column (--column, default the second); or, with --rate HZ, the output\n"
            "column alone (text or binary --format), sample i (from 0) at time (i + 1)/HZ.\n"
            "Bands: at rate |rate error| <= --rate-band x |input rate| (a fraction, e.g. 0.001);\n"
            "at rest |indicated rate| <= --rest-band deg/h. --smoothing S averages into S-second windows\n"
            "from power-on (stamped at their end) before the test.\n"
            "JSON: " + std::string(warm_up ? "warm_up_time" : "turn_on_time") + " (s), longest_run, runs.");
    command->add_option("--run", arguments->runs, "INPUT_RATE_DEG_S:FILE, once per power-on run")->required();
    command->add_option("--scale-factor", arguments->options.scale_factor, "K, output units per deg/s")->required();
    command->add_option("--zero", arguments->options.zero_output, "calibrated zero output F0 (output units)")
        ->capture_default_str();
    command->add_option("--rate-band", arguments->options.rate_band, "allowed rate error relative to the input rate");
    command->add_option("--rest-band", arguments->options.rest_band_deg_h, "allowed indicated rate at rest, deg/h");
    command->add_option("--smoothing", arguments->options.smoothing_s, "averaging window before the test, s");
    command->add_option("--rate", arguments->sample_rate_hz, "sample rate, Hz (records without a time column)");
    command->add_option("--time-column", arguments->time_column, "time column by name or 1-based index");
    add_record_options(*command, arguments->source);
    command->add_flag("--remove-earth-rate", arguments->remove_earth_rate,
                      "remove the Earth rate along the IRA (from --latitude, --heading, --elevation)");
    add_axis_options(*command, arguments->axis);
    command->add_flag("--json", arguments->json, "print one JSON object on stdout");
    return [arguments] {
      TurnOnTimeOptions options = arguments->options;
      if (arguments->remove_earth_rate) options.earth_rate = arguments->axis;
      options.validate();
      std::vector<PowerOnRun> runs;
      for (const auto& text : arguments->runs) {
        auto [rate, file] = parse_number_and_file(text, "--run", "100:power_on_100dps.txt");
        OutputRecordSource source = arguments->source;
        source.path = file;
        TimedRecord record = read_timed_record(source, arguments->sample_rate_hz, arguments->time_column, 2);
        runs.push_back({file, rate, std::move(record.time_s), std::move(record.output)});
      }
      const TurnOnTimeResult result = turn_on_time(runs, options);
      print_result(result.to_json(), result.report(), arguments->json);
      return 0;
    };
  };
}

const bool registered_turn_on = register_command("turn-on-time", make_setup(false));
const bool registered_warm_up = register_command("warm-up-time", make_setup(true));

}  // namespace
}  // namespace inertest::cli

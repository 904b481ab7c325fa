// Plan kind "bandwidth": GJB 2426A-2004 5.13-5.14 (bandwidth and output delay).
// Exactly one of:
//   file = "gains.csv"            # header freq_hz,gain,phase_deg (phase against the input rate)
//   [[procedure.run]]             # one raw record per frequency, increasing
//   frequency_hz = 10.0
//   file = "vib_10Hz.csv"
// Keys for records:
//   time_column = "time_s", output_column = "output", angle_column = "angle_deg",
//   angle_unit = "deg"
// minimum_frequencies = 10        # optional; 5.13.3 a) asks for at least 10
#include "campaign/step_registry.h"
#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/bandwidth_and_delay.h"

namespace inertest::campaign {
namespace {

struct Source {
  std::string gains_file;
  std::vector<ListedFile> runs;
  std::string time_column = "time_s";
  std::string output_column = "output";
  std::string angle_column = "angle_deg";
};

StepAction prepare(PlanTable& step, const PlanContext& context) {
  Source source;
  BandwidthOptions options;
  source.gains_file = step.optional_file("file").value_or("");
  for (auto& run : step.tables("run")) {
    const double frequency = run.number("frequency_hz");
    if (!(frequency > 0.0)) run.fail_at("frequency_hz", "must be positive");
    if (!source.runs.empty() && !(frequency > source.runs.back().key)) {
      run.fail_at("frequency_hz", "must be above the previous run's; the frequencies must increase");
    }
    const std::string file = run.file("file");
    run.require_all_used();
    const auto& begin = run.raw().source().begin;
    source.runs.push_back({frequency, file,
                           SourceLocation{step.plan_path(), static_cast<std::size_t>(begin.line),
                                          static_cast<std::size_t>(begin.column)}});
  }
  if (source.gains_file.empty() == source.runs.empty()) {
    step.fail("give exactly one of 'file' (gains table) or [[procedure.run]] (raw records)");
  }
  if (!source.runs.empty()) {
    source.time_column = step.string_or("time_column", source.time_column);
    source.output_column = step.string_or("output_column", source.output_column);
    source.angle_column = step.string_or("angle_column", source.angle_column);
    options.angle_unit = step.string_or("angle_unit", options.angle_unit);
  }
  const double minimum = step.number_or("minimum_frequencies", static_cast<double>(options.minimum_frequencies));
  if (minimum < 3 || minimum != static_cast<double>(static_cast<std::size_t>(minimum))) {
    step.fail_at("minimum_frequencies", "must be a whole number >= 3");
  }
  options.minimum_frequencies = static_cast<std::size_t>(minimum);
  options.output_unit = context.instrument.output_unit;
  try {
    options.validate();
  } catch (const Error& e) {
    step.fail(e.message());
  }
  if (!source.runs.empty() && source.runs.size() < options.minimum_frequencies) {
    step.fail("names " + std::to_string(source.runs.size()) + " frequencies; GJB 2426A 5.13.3 a) asks for at least " +
              std::to_string(options.minimum_frequencies));
  }
  return [source, options](const StepRunContext&) {
    if (!source.gains_file.empty()) return bandwidth_and_delay(read_frequency_response(source.gains_file), options).to_json();
    const auto records =
        read_angular_vibration_records(source.runs, source.time_column, source.output_column, source.angle_column);
    return bandwidth_and_delay(std::span<const AngularVibrationRecord>(records), options).to_json();
  };
}

const bool registered = register_step("bandwidth", prepare);

}  // namespace
}  // namespace inertest::campaign

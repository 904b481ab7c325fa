// Plan kind "scale_factor": GJB 2426A-2004 5.8.1-5.8.3 from test points or raw records.
// Exactly one of:
//   file = "points.csv"        # header rate,output (one row per test point, in test order)
//   record = "run.csv"         # one long record with a table-rate column, cut into segments
//   [[procedure.run]]          # a record per test point, in test order:
//   rate = 100.0               #   its table rate
//   file = "p100.csv"          #   its record (the output column)
// Keys for records:
//   rate_column = "rate"       # record only; header name or 1-based index
//   output_column = "output"
//   sample_rate_hz = 100.0     # default: [instrument] sample_rate_hz
//   settling_time_s = 0.0      # dropped at the start of a record / after each change of rate
//   minimum_segment_s = 1.0    # record only: shorter constant-rate segments are skipped
//   rate_tolerance = 1e-3      # record only, in rate_unit
// rate_unit = "deg/s"          # optional
#include "campaign/step_registry.h"
#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/scale_factor.h"

namespace inertest::campaign {
namespace {

struct Source {
  std::string points_file;
  std::string record_file;
  std::vector<ListedFile> point_records;
  std::string rate_column = "rate";
  std::string output_column = "output";
  RateSegmentOptions segments;
};

StepAction prepare(PlanTable& step, const PlanContext& context) {
  Source source;
  ScaleFactorOptions options;
  source.points_file = step.optional_file("file").value_or("");
  source.record_file = step.optional_file("record").value_or("");
  for (auto& run : step.tables("run")) {
    const double rate = run.number("rate");
    const std::string file = run.file("file");
    run.require_all_used();
    const auto& begin = run.raw().source().begin;
    source.point_records.push_back({rate, file,
                                    SourceLocation{step.plan_path(), static_cast<std::size_t>(begin.line),
                                                   static_cast<std::size_t>(begin.column)}});
  }
  const int sources = !source.points_file.empty() + !source.record_file.empty() + !source.point_records.empty();
  if (sources != 1) step.fail("give exactly one of 'file' (test points), 'record' or [[procedure.run]] (records)");
  const bool records = source.points_file.empty();
  if (records) {
    source.output_column = step.string_or("output_column", source.output_column);
    const auto sample_rate = step.optional_number("sample_rate_hz");
    if (!sample_rate && !context.instrument.sample_rate_hz) {
      step.fail("raw records need 'sample_rate_hz' here or in [instrument]");
    }
    source.segments.timing.sample_rate_hz = sample_rate ? *sample_rate : *context.instrument.sample_rate_hz;
    source.segments.timing.settling_time_s = step.number_or("settling_time_s", 0.0);
  }
  if (!source.record_file.empty()) {
    source.rate_column = step.string_or("rate_column", source.rate_column);
    source.segments.minimum_segment_s = step.number_or("minimum_segment_s", source.segments.minimum_segment_s);
    source.segments.rate_tolerance = step.number_or("rate_tolerance", source.segments.rate_tolerance);
  }
  options.rate_unit = step.string_or("rate_unit", options.rate_unit);
  options.output_unit = context.instrument.output_unit;
  try {
    options.validate();
    if (!source.record_file.empty()) {
      source.segments.validate();
    } else if (records) {
      source.segments.timing.validate();
    }
  } catch (const Error& e) {
    step.fail(e.message());
  }
  return [source, options](const StepRunContext&) {
    std::vector<ScaleFactorPoint> points;
    if (!source.points_file.empty()) {
      points = read_scale_factor_points(source.points_file);
    } else if (!source.record_file.empty()) {
      points = read_scale_factor_record(source.record_file, source.rate_column, source.output_column, source.segments);
    } else {
      points = read_scale_factor_point_records(source.point_records, source.output_column, source.segments.timing);
    }
    return scale_factor(points, options).to_json();
  };
}

const bool registered = register_step("scale_factor", prepare);

}  // namespace
}  // namespace inertest::campaign

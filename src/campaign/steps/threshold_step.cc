// Plan kind "threshold": GJB 2426A-2004 5.10 (latitude from [site]).
//   method = 1                # 1 rate table, 2 dividing head, 3 slow rotation
//   file = "threshold.csv"    # method 1: header rate,output; method 2: angle_deg,output;
//                             # method 3: the record of one revolution (time + output, or sample_rate_hz)
//   scale_factor = 5000       # optional, output units per deg/s, default [instrument] nominal
//   zero_output = 0.0         # optional (see threshold.h for what is used without it)
//   criterion_denominator = "expected"   # optional: "expected" (IEEE Std 952-1997, default) or
//                             # "measured" (GJB 2426A-2004 eq. (15) as printed)
//   rate_unit = "deg/s"       # optional, method 1
//   heading_deg = 0           # optional, methods 2 and 3, default [site] heading_deg
//   table_rate_deg_s = 0.1    # method 3
//   sample_rate_hz, time_column, column, format   # method 3 record layout
#include "campaign/steps/record_keys.h"
#include "inertest/io/text_table.h"
#include "inertest/procedures/threshold.h"

namespace inertest::campaign {
namespace {

std::vector<std::vector<double>> read_columns(const std::string& file, const char* first, const char* second) {
  TextTableOptions read;
  read.header = TextTableOptions::Header::kPresent;
  read.columns = {ColumnSelector{first}, ColumnSelector{second}};
  return read_text_table(file, read).columns;
}

StepAction prepare(PlanTable& step, const PlanContext& context) {
  const double method_number = step.number("method");
  if (method_number != 1 && method_number != 2 && method_number != 3) step.fail_at("method", "must be 1, 2 or 3");
  const int method = static_cast<int>(method_number);
  const std::string file = step.file("file");
  ThresholdOptions options;
  options.scale_factor = read_scale_factor(step, context);
  options.zero_output = step.optional_number("zero_output");
  const std::string denominator = step.string_or("criterion_denominator", "expected");
  try {
    options.criterion_denominator = parse_criterion_denominator(denominator);
  } catch (const Error& e) {
    step.fail_at("criterion_denominator", e.message());
  }
  options.latitude_deg = context.site.latitude_deg;
  if (method == 1) {
    options.rate_unit = step.string_or("rate_unit", options.rate_unit);
  } else {
    options.heading_deg = step.number_or("heading_deg", context.site.heading_deg);
  }
  double table_rate = 0.0;
  std::optional<double> sample_rate;
  std::string time_column;
  OutputRecordSource source;
  if (method == 3) {
    table_rate = step.number("table_rate_deg_s");
    if (table_rate == 0.0) step.fail_at("table_rate_deg_s", "must be nonzero");
    sample_rate = step.optional_number("sample_rate_hz");
    if (sample_rate && !(*sample_rate > 0.0)) step.fail_at("sample_rate_hz", "must be positive");
    time_column = step.string_or("time_column", "");
    source = read_record_keys(step, file);
  }
  check_in_plan(step, [&] { options.validate(); });
  return [=](const StepRunContext&) {
    if (method == 1) {
      const auto columns = read_columns(file, "rate", "output");
      std::vector<RateTablePoint> points;
      for (std::size_t i = 0; i < columns[0].size(); ++i) points.push_back({columns[0][i], columns[1][i]});
      return threshold_rate_table(points, options).to_json();
    }
    if (method == 2) {
      const auto columns = read_columns(file, "angle_deg", "output");
      std::vector<DividingHeadPoint> points;
      for (std::size_t i = 0; i < columns[0].size(); ++i) points.push_back({columns[0][i], columns[1][i]});
      return threshold_dividing_head(points, options).to_json();
    }
    const TimedRecord record = read_timed_record(source, sample_rate, time_column, 4);
    return threshold_rotating(record.time_s, record.output, table_rate, options).to_json();
  };
}

const bool registered = register_step("threshold", prepare);

}  // namespace
}  // namespace inertest::campaign

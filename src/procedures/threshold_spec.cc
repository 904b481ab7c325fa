// The threshold procedure's one description (issue 22): the CLI command `inertest threshold`, the
// plan kind "threshold", its JSON and its text report are all generated from it. One file input
// whose layout the method gives.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/io/binary_record.h"
#include "inertest/io/output_record.h"
#include "inertest/io/text_table.h"
#include "inertest/procedures/threshold.h"
#include "inertest/procedures/instrument_sensor.h"
#include "procedures/fifty_percent_criterion.h"

namespace inertest {
namespace {

// The procedure's options, the method and how method 3's record is stored.
struct ThresholdInputOptions {
  ThresholdOptions threshold;
  std::size_t method = 0;
  double table_rate_deg_s = 0.0;
  std::optional<double> sample_rate_hz;  // absent: the record has a time column
  std::string time_column;
  std::string column;
  std::string format;
};

// The rows of a table with the header `first,second` (methods 1 and 2) as points.
template <typename Point>
std::vector<Point> read_points(const std::string& file, const char* first, const char* second) {
  TextTableOptions read;
  read.header = TextTableOptions::Header::kPresent;
  read.columns = {ColumnSelector{first}, ColumnSelector{second}};
  const auto columns = read_text_table(file, read).columns;
  std::vector<Point> points;
  for (std::size_t i = 0; i < columns[0].size(); ++i) points.push_back({columns[0][i], columns[1][i]});
  return points;
}

// Each direction's candidate and every input with its 50 % test, outputs in the zero output's unit.
nlohmann::json branches_json(const ThresholdResult& result) {
  const std::string& unit = result.zero_output.unit;  // the instrument's output unit
  return criterion::branches_json(result.branches, [&](const ThresholdPoint& p) {
    return nlohmann::json{{"input", Figure{p.input_deg_h, "deg/h", std::nullopt}},
                          {"expected_output", Figure{p.expected_output, unit, std::nullopt}},
                          {"output", Figure{p.output, unit, std::nullopt}},
                          {"relative_error", p.relative_error},
                          {"satisfies", p.satisfies}};
  });
}

}  // namespace

ProcedureSpec threshold_spec() {
  using Options = ThresholdInputOptions;
  return ProcedureDefinition<Options, ThresholdResult>(
             "threshold", "Threshold", "GJB 2426A-2004 5.10, eqs. (14)-(17)",
             "K in output units per deg/s. The 50 % criterion is relative to the expected output\n"
             "(IEEE Std 952-1997) unless --criterion-denominator measured (eq. 15 as printed, relative to the\n"
             "measured output).\n"
             "--method 1: FILE has the header 'rate,output' (table rate, --rate-unit, default deg/s; mean output);\n"
             "  zero-rate rows give the zero output unless --zero.\n"
             "--method 2: FILE has the header 'angle_deg,output' (dividing-head angle of the IRA from north, plus\n"
             "  --heading; mean output); Omega = Omega_e cos(latitude) cos(angle). East/west rows give the zero\n"
             "  unless --zero.\n"
             "--method 3: FILE is the record of one slow revolution: a time column (s) and an output column, or\n"
             "  the output alone with --rate HZ; --table-rate is the rate (deg/s) at which the IRA azimuth grows,\n"
             "  --heading its azimuth at t = 0; the zero is the record's mean unless --zero.\n"
             "In a plan the latitude is [site]'s and the heading defaults to [site]'s.")
      .chinese_title("阈值")
      .report_method(
          "The input is decreased step by step; the threshold is the smallest input whose output is within 50 % of the expected output K·Ω (IEEE Std 952-1997; GJB 2426A eq. (15) as printed, relative to the measured output, on request), the largest over the directions.",
          "逐级减小输入角速度；阈值为输出与理论输出 K·Ω 之差不超过理论输出 50 % 的最小输入（IEEE Std 952-1997；按需采用 GJB 2426A 式 (15) 原式，相对实测输出），取各方向中的最大值。")
      .input(InputSpec("file", "test points or record").read_from_file("FILE", "file").holds_raw_samples())
      .parameter(
          ParameterSpec("method", "1 (rate table), 2 (dividing head), 3 (slow rotation)")
              .one_of({"1", "2", "3"})
              .required_on_command_line(),
          &Options::method)
      .parameter(ParameterSpec("scale_factor", "K")
                     .unit_is("output units per deg/s")
                     .required_on_command_line()
                     .instrument_gives("nominal_scale_factor")
                     .instrument_gives_if(instrument_is_gyro),
                 &Options::threshold, &ThresholdOptions::scale_factor)
      .parameter(
          ParameterSpec("zero", "zero output (output at zero input; pulse/s for a pulse counter)").plan_key_is("zero_output"),
          [](Options& options, const nlohmann::json& value) { options.threshold.zero_output = value.get<double>(); })
      .parameter(ParameterSpec("criterion_denominator",
                               "50 % criterion relative to the 'expected' output (IEEE Std 952-1997) or the "
                               "'measured' one (GJB 2426A eq. 15 as printed)")
                     .one_of({"expected", "measured"}),
                 "expected",
                 [](Options& options, const nlohmann::json& value) {
                   options.threshold.criterion_denominator = parse_criterion_denominator(value.get<std::string>());
                 })
      .parameter(ParameterSpec("rate_unit", "method 1: unit of the rate column"), &Options::threshold,
                 &ThresholdOptions::rate_unit)
      .parameter(
          ParameterSpec("latitude", "site latitude (methods 2, 3)").unit_is("deg").site_gives("latitude_deg", true),
          &Options::threshold, &ThresholdOptions::latitude_deg)
      .parameter(
          ParameterSpec("heading", "method 2: azimuth of the dividing head's zero; method 3: IRA azimuth at t = 0")
              .unit_is("deg")
              .plan_key_is("heading_deg")
              .site_gives("heading_deg"),
          &Options::threshold, &ThresholdOptions::heading_deg)
      .parameter(ParameterSpec("table_rate", "method 3: table rate")
                     .unit_is("deg/s")
                     .plan_key_is("table_rate_deg_s")
                     .needed_for("method 3"),
                 &Options::table_rate_deg_s)
      .parameter(ParameterSpec("rate", "method 3: sample rate (record without time column)")
                     .unit_is("Hz")
                     .plan_key_is("sample_rate_hz"),
                 [](Options& options, const nlohmann::json& value) { options.sample_rate_hz = value.get<double>(); })
      .parameter(ParameterSpec("time_column", "method 3: time column by name or 1-based index"), &Options::time_column)
      .parameter(ParameterSpec("column", "method 3: the output column by header name or 1-based index"),
                 &Options::column)
      .parameter(ParameterSpec("format",
                               "method 3: binary record instead of text: f64, f32, i32 or i16, optionally "
                               "with le/be (e.g. f32be)"),
                 &Options::format)
      .parameter(ParameterSpec("output_unit", "instrument output unit").instrument_gives("output_unit", true),
                 &Options::threshold, &ThresholdOptions::output_unit)
      .field({"threshold", FieldRole::headline, "threshold", "阈值", "eqs. (14)-(17)"}, &ThresholdResult::threshold)
      .field({"method", FieldRole::detail, "method", "方法", "5.10.4"}, &ThresholdResult::method)
      .field_from({"criterion_denominator", FieldRole::hidden, "criterion denominator", "判据分母", "eq. (15)"},
                  [](const ThresholdResult& result) { return to_string(result.criterion_denominator); })
      .field_from({"criterion", FieldRole::detail, "criterion", "判据", "eq. (15)"},
                  [](const ThresholdResult& result) { return criterion_text(result.criterion_denominator); })
      .field({"zero_output", FieldRole::detail, "zero output", "零位输出", "5.10.4"}, &ThresholdResult::zero_output)
      .field_from({"branches", FieldRole::table, "candidate per direction", "各方向候选值", "eqs. (14)-(17)"},
                  branches_json)
      .field_from({"clause", FieldRole::hidden, "clause", "条款", ""},
                  [](const ThresholdResult& result) {
                    return fmt::format("GJB 2426A-2004 5.10.4.{}, eqs. (14)-(17); IEEE Std 952-1997", result.method);
                  })
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &ThresholdResult::warnings)
      .checked_by([](const ProcedureCall&, const Options& options) {
        if (options.method < 1 || options.method > 3) {
          throw ParameterError("method", "must be 1 (rate table), 2 (dividing head) or 3 (slow rotation)");
        }
        options.threshold.validate();
        // Before anything runs (a plan names [site] latitude_deg): methods 2 and 3 take the Earth rate's input.
        if (options.method != 1) options.threshold.latitude_for(options.method == 2 ? "method 2" : "method 3");
        if (options.method != 3) return;
        if (options.table_rate_deg_s == 0.0) throw ParameterError("table_rate", "must be nonzero with method 3");
        if (options.sample_rate_hz && !(*options.sample_rate_hz > 0.0))
          throw ParameterError("rate", "must be positive");
        if (!options.format.empty()) check_parameter("format", [&] { BinaryFormat::parse(options.format); });
      })
      .unit_of("threshold", "deg/h")
      .compute([](const ProcedureCall& call, const Options& options) {
        const std::string& file = call.files.at("file");
        if (options.method == 1)
          return threshold_rate_table(read_points<RateTablePoint>(file, "rate", "output"), options.threshold);
        if (options.method == 2) {
          return threshold_dividing_head(read_points<DividingHeadPoint>(file, "angle_deg", "output"),
                                         options.threshold);
        }
        OutputRecordSource source;
        source.path = file;
        source.column = options.column;
        source.format = options.format;
        ProcedureCall reading;  // the record readers of a timed input, for the unit the record stores
        set_record_readers(reading, source, 4, options.sample_rate_hz, options.time_column);
        require_raw_output(reading, file, options.threshold.output_unit, "method 3 divides the output by K");
        TimedRecord record = read_timed_record(source, options.sample_rate_hz, options.time_column, 4);
        if (call.pulse_counts) pulse_counts_as_rates(record, options.sample_rate_hz);
        return threshold_rotating(record.time_s, record.output, options.table_rate_deg_s, options.threshold);
      });
}

}  // namespace inertest

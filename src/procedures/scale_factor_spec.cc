// The scale factor procedure's one description (issue 22): the CLI command `inertest scale-factor`,
// the plan kind "scale_factor", its JSON and its text report are all generated from it.
#include <nlohmann/json.hpp>

#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/scale_factor.h"

namespace inertest {
namespace {

// The procedure's options and how its raw records are read (the columns, eq. (1)'s timing and the
// segments of one long record).
struct ScaleFactorInputOptions {
  ScaleFactorOptions scale_factor;
  std::string rate_column = "rate";
  std::string output_column = "output";
  RecordTiming timing;
  RateSegmentOptions segments;
};

}  // namespace

ProcedureSpec scale_factor_spec() {
  using Options = ScaleFactorInputOptions;
  return ProcedureDefinition<Options, ScaleFactorResult>(
             "scale_factor", "Scale factor", "GJB 2426A-2004 5.8.1-5.8.3, eqs. (1)-(11)",
             "K, zero offset F0, nonlinearity, asymmetry.\n"
             "POINTS has the header 'rate,output': one row per test point in test order; rate is the table\n"
             "rate (signed, --rate-unit, default deg/s), output the mean instrument output at that rate.\n"
             "Zero-rate rows before the first and after the last nonzero rate are the static runs.\n"
             "Instead of POINTS, raw records (the mean after --settling-time is F_j of eq. 1):\n"
             "  --record FILE: one long record with a table-rate column (--rate-column) and the output\n"
             "    (--output-column), cut into constant-rate segments: rates within --rate-tolerance of the\n"
             "    segment's mean rate so far belong to it (3 outside in a row end it; a lone one is a glitch,\n"
             "    left out), segments shorter than --minimum-segment s, or whose rate moves across them by\n"
             "    half the tolerance, are skipped (ramps), and a segment whose rate is within the tolerance\n"
             "    of zero is a static run.\n"
             "  --records LIST: a CSV with the header 'rate,file', one record per test point in test\n"
             "    order (paths relative to LIST), each with the output column --output-column.\n"
             "  Both need --sample-rate (Hz). Columns are header names or 1-based indexes.")
      .chinese_title("标度因数")
      .report_method(
          "The mean static output of the runs before and after the rate sequence is subtracted from the mean output at each table rate; a least-squares line through these gives the scale factor K and the zero offset F0. The nonlinearity is the largest deviation of a point from the line relative to the largest output; the asymmetry compares the slopes fitted to the positive and to the negative rates alone.",
          "以转速序列前、后静态测试输出的平均值作为零位，从各转台角速度下的输出平均值中扣除；对其作最小二乘直线拟合得标度因数 K 和零位 F0。各点相对拟合直线的最大偏差与最大输出之比为标度因数非线性度；正、负输入角速度分别拟合的标度因数之差为标度因数不对称性。")
      .input(InputSpec("points", "CSV of test points (rate,output)")
                 .read_from_file("POINTS", "file")
                 .alternative_in("data"))
      .input(InputSpec("record", "one long record with a table-rate column")
                 .read_from_file("--record", "record")
                 .holds_raw_samples()
                 .alternative_in("data"))
      .input(InputSpec("point_records", "a record per test point, in test order")
                 .numbered_runs("rate", "100:p100.csv")
                 .listed_on_command_line("--records")
                 .holds_raw_samples()
                 .alternative_in("data"))
      .parameter(ParameterSpec("rate_column", "table-rate column of the long record"), &Options::rate_column)
      .parameter(ParameterSpec("output_column", "output column of the records"), &Options::output_column)
      .parameter(ParameterSpec("sample_rate", "sample rate of the records")
                     .unit_is("Hz")
                     .plan_key_is("sample_rate_hz")
                     .instrument_gives("sample_rate_hz")
                     .needed_for("--record and --records"),
                 &Options::timing, &RecordTiming::sample_rate_hz)
      .parameter(ParameterSpec("settling_time", "dropped at the start of each record / after each change of rate")
                     .unit_is("s")
                     .plan_key_is("settling_time_s"),
                 &Options::timing, &RecordTiming::settling_time_s)
      .parameter(ParameterSpec("minimum_segment", "shortest constant-rate segment of the long record")
                     .unit_is("s")
                     .plan_key_is("minimum_segment_s"),
                 &Options::segments, &RateSegmentOptions::minimum_segment_s)
      .parameter(ParameterSpec("rate_tolerance", "rate tolerance of a segment of the long record, rate unit"),
                 &Options::segments, &RateSegmentOptions::rate_tolerance)
      .parameter(ParameterSpec("rate_unit", "unit of the rates"), &Options::scale_factor,
                 &ScaleFactorOptions::rate_unit)
      .parameter(ParameterSpec("output_unit", "instrument output unit, e.g. pulse/s or V")
                     .instrument_gives("output_unit", true),
                 &Options::scale_factor, &ScaleFactorOptions::output_unit)
      .field({"scale_factor", FieldRole::headline, "scale factor K", "标度因数", "eq. (5)"},
             &ScaleFactorResult::scale_factor)
      .field({"zero_offset", FieldRole::detail, "zero offset F0", "零位 F0", "eq. (6)"},
             &ScaleFactorResult::zero_offset)
      .field({"nonlinearity", FieldRole::headline, "nonlinearity Kn", "标度因数非线性度", "eq. (9)"},
             &ScaleFactorResult::nonlinearity)
      .field({"asymmetry", FieldRole::headline, "asymmetry Ka", "标度因数不对称性", "eqs. (10)-(11)"},
             &ScaleFactorResult::asymmetry)
      .field({"scale_factor_positive", FieldRole::detail, "scale factor K(+)", "正向标度因数", "eqs. (5)-(6)"},
             &ScaleFactorResult::scale_factor_positive)
      .field({"scale_factor_negative", FieldRole::detail, "scale factor K(-)", "负向标度因数", "eqs. (5)-(6)"},
             &ScaleFactorResult::scale_factor_negative)
      .field({"static_output_start", FieldRole::detail, "static output at start", "起始静态输出", "eq. (2)"},
             &ScaleFactorResult::static_output_start)
      .field({"static_output_end", FieldRole::detail, "static output at end", "结束静态输出", "eq. (2)"},
             &ScaleFactorResult::static_output_end)
      .field({"fit_residual_rms", FieldRole::detail, "fit residual rms", "拟合残差均方根", "eq. (4)"},
             &ScaleFactorResult::fit_residual_rms)
      .field_from({"nonlinearity_curve", FieldRole::curve, "nonlinearity curve", "非线性度曲线", "eq. (8)", {"rate", "deviation"}},
                  [](const ScaleFactorResult& result) {
                    nlohmann::json curve = nlohmann::json::array();
                    for (const auto& point : result.nonlinearity_curve) {
                      curve.push_back({{"rate", Figure{point.rate, result.rate_unit, std::nullopt}},
                                       {"deviation", Figure{point.deviation, "ppm", std::nullopt}}});
                    }
                    return curve;
                  })
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &ScaleFactorResult::warnings)
      .checked_by([](const ProcedureCall& call, const Options& options) {
        options.scale_factor.validate();
        if (call.files.contains("points")) return;
        if (!(options.timing.sample_rate_hz > 0.0)) {
          throw Error(
              "raw records need the sample rate (--sample-rate; in a plan sample_rate_hz here or in [instrument])");
        }
        options.timing.validate();
        if (call.files.contains("record")) {
          RateSegmentOptions segments = options.segments;
          segments.timing = options.timing;
          segments.validate();
        }
      })
      .unit_of("nonlinearity", "ppm")
      .unit_of("asymmetry", "ppm")
      .unit_of("scale_factor", "{output_unit}/({rate_unit})")
      .unit_of("scale_factor_positive", "{output_unit}/({rate_unit})")
      .unit_of("scale_factor_negative", "{output_unit}/({rate_unit})")
      .unit_of("zero_offset", "{output_unit}")
      .unit_of("static_output_start", "{output_unit}")
      .unit_of("static_output_end", "{output_unit}")
      .unit_of("fit_residual_rms", "{output_unit}")
      .compute([](const ProcedureCall& call, const Options& options) {
        if (call.files.contains("points"))
          return scale_factor(read_scale_factor_points(call.files.at("points")), options.scale_factor);
        std::vector<ScaleFactorPoint> points;
        if (call.files.contains("record")) {
          RateSegmentOptions segments = options.segments;
          segments.timing = options.timing;
          points = read_scale_factor_record(call.files.at("record"), options.rate_column, options.output_column, segments);
        } else {
          points = read_scale_factor_point_records(listed_files(call.runs.at("point_records")), options.output_column,
                                                   options.timing);
        }
        // Pulse counts per sample interval become pulse/s, as bias reads them: K is per deg/s (eq. 5).
        if (call.pulse_counts) {
          for (ScaleFactorPoint& point : points) point.output *= options.timing.sample_rate_hz;
        }
        return scale_factor(points, options.scale_factor);
      });
}

}  // namespace inertest

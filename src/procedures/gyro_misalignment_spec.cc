// Gyro misalignment separation on a single-axis rate table (the misalignment paper,
// core/citations.h; inertest/misalignment/gyro_misalignment.h), declared once (issue 22): the
// command `inertest misalignment gyro`, the plan kind "gyro_misalignment", the JSON, the text and the
// report come from this file.
#include <nlohmann/json.hpp>

#include "inertest/core/citations.h"
#include "inertest/io/output_record.h"
#include "inertest/misalignment/gyro_misalignment.h"
#include "inertest/misalignment/misalignment_files.h"
#include "inertest/procedures/instrument_sensor.h"

namespace inertest {
namespace {

// The options, and whether POSITIONS lists raw records to average over whole revolutions.
struct GyroMisalignmentInputOptions {
  GyroMisalignmentOptions misalignment;
  bool records = false;
};

}  // namespace

ProcedureSpec gyro_misalignment_spec() {
  using Options = GyroMisalignmentInputOptions;
  using Result = GyroMisalignmentResult;
  return ProcedureDefinition<Options, Result>(
             "gyro_misalignment", "Gyro misalignment separation (rate table)",
             "the misalignment paper, least squares on V(+) - V(-)",
             "Gyro on a single-axis rate table, fixture turned beta, gyro turned alpha, table at +w and -w.\n"
             "POSITIONS has the header 'alpha_deg,beta_deg,rate_dps,output': one row per position and\n"
             "direction (sign of rate_dps), output averaged over whole revolutions; any number of rates.\n"
             "With --records, POSITIONS is 'alpha_deg,beta_deg,rate_dps,file' and each file a record with\n"
             "'output' and 'table_angle_deg' or 'time_s'; the tool averages whole revolutions itself.\n"
             "Least squares on V(+) - V(-) = 2 kI w (-dy0 cos b + dx0 sin b - dy1 + dz2 sin a - dy2 cos a).\n"
             "Outputs (arcsec): delta_theta_y0, delta_theta_x0, delta_theta_y1, delta_theta_y2, delta_theta_z2,\n"
             "misalignment (all rates together), by_rate (the same per rate, with rate_dps).\nSource: " +
                 std::string(citations::kMisalignmentPaper) + ".")
      .command_is("misalignment", "gyro",
                  "Separate an instrument's input-axis misalignment from the table's and the fixture's errors.\n"
                  "Angles in arcsec. Source: " +
                      std::string(citations::kMisalignmentPaper) + ".")
      .chinese_title("陀螺失准角分离（速率转台）")
      .report_method(
          "The gyro turns at +ω and −ω in five positions (α, β) of the fixture on a single-axis rate table; the "
          "differences V(+) − V(−) give the table, fixture and input-axis error angles by least squares.",
          "陀螺在单轴速率转台上以 +ω、−ω 分别在五个夹具位置 (α, β) 测试；由 V(+) − V(−) "
          "以最小二乘法分离台面、夹具面和输入轴失准角。")
      .input(InputSpec("positions", "CSV of positions (or of records with --records)").read_from_file("POSITIONS", "file").holds_raw_samples())
      .parameter(ParameterSpec("scale_factor", "kI, output units per deg/s")
                     .required_on_command_line()
                     .instrument_gives("nominal_scale_factor")
                     .instrument_gives_if(instrument_is_gyro),
                 &Options::misalignment, &GyroMisalignmentOptions::scale_factor)
      .parameter(ParameterSpec("output_unit", "instrument output unit, e.g. V").instrument_gives("output_unit", true),
                 &Options::misalignment, &GyroMisalignmentOptions::output_unit)
      .parameter(ParameterSpec("records", "POSITIONS lists raw records to average over whole revolutions"),
                 &Options::records)
      .figure_from({"delta_theta_y0", FieldRole::detail, "Δθy0 (table face)", "Δθy0（台面）", "paper, w_I"},
                   [](const Result& r) { return r.combined.angles.delta_theta_y0; })
      .figure_from({"delta_theta_x0", FieldRole::detail, "Δθx0 (table face)", "Δθx0（台面）", "paper, w_I"},
                   [](const Result& r) { return r.combined.angles.delta_theta_x0; })
      .figure_from({"delta_theta_y1", FieldRole::detail, "Δθy1 (fixture face)", "Δθy1（夹具面）", "paper, w_I"},
                   [](const Result& r) { return r.combined.angles.delta_theta_y1; })
      .figure_from({"delta_theta_y2", FieldRole::headline, "Δθy2 (input axis)", "Δθy2（输入轴）", "paper, w_I"},
                   [](const Result& r) { return r.combined.angles.delta_theta_y2; })
      .figure_from({"delta_theta_z2", FieldRole::headline, "Δθz2 (input axis)", "Δθz2（输入轴）", "paper, w_I"},
                   [](const Result& r) { return r.combined.angles.delta_theta_z2; })
      .figure_from({"misalignment", FieldRole::headline, "misalignment γ", "失准角 γ", "γ = √(Δθy2² + Δθz2²)"},
                   [](const Result& r) { return r.combined.angles.misalignment; })
      .figure_from({"scale_factor", FieldRole::detail, "scale factor kI", "标度因数 kI", ""},
                   [](const Result& r) { return Figure{r.scale_factor, r.output_unit + "/(deg/s)", std::nullopt}; })
      .field_from({"equation_count", FieldRole::detail, "position pairs", "位置对数", ""},
                  [](const Result& r) { return r.combined.equation_count; })
      .field_from({"degrees_of_freedom", FieldRole::detail, "degrees of freedom", "自由度", ""},
                  [](const Result& r) { return r.combined.degrees_of_freedom; })
      .figure_from({"residual_rms", FieldRole::detail, "rms residual", "残差均方根", ""},
                   [](const Result& r) { return r.combined.residual_rms; })
      .field_from({"residuals", FieldRole::table, "residual of each position", "各位置残差", ""},
                  [](const Result& r) { return gyro_fit_json(r.combined).at("residuals"); })
      .field_from({"by_rate", FieldRole::table, "solution at each rate", "各转速解", ""}, by_rate_json)
      .field_from({"source", FieldRole::hidden, "source", "来源", ""},
                  [](const Result&) {
                    return std::string(citations::kMisalignmentPaper) +
                           ", gyro on a rate table; least squares on V(+) - V(-) = 2 kI w (-dy0 cos b + dx0 sin b - "
                           "dy1 + dz2 sin a - dy2 cos a)";
                  })
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &Result::warnings)
      .checked_by([](const ProcedureCall&, const Options& options) { options.misalignment.validate(); })
      .unit_of("delta_theta_y0", "arcsec")
      .unit_of("delta_theta_x0", "arcsec")
      .unit_of("delta_theta_y1", "arcsec")
      .unit_of("delta_theta_y2", "arcsec")
      .unit_of("delta_theta_z2", "arcsec")
      .unit_of("misalignment", "arcsec")
      .unit_of("residual_rms", "arcsec")
      .unit_of("scale_factor", "{output_unit}/(deg/s)")
      .compute([](const ProcedureCall& call, const Options& options) {
        const std::string& file = call.files.at("positions");
        GyroMisalignmentOptions misalignment = options.misalignment;
        misalignment.source = file;
        return gyro_misalignment(
            options.records ? read_gyro_misalignment_records(file, call.pulse_counts) : read_gyro_misalignment_positions(file),
            misalignment);
      });
}

}  // namespace inertest

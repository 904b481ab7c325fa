// Accelerometer misalignment by the multi-position gravity test (the misalignment paper,
// core/citations.h; inertest/misalignment/accelerometer_misalignment.h), declared once (issue 22):
// the command `inertest misalignment accelerometer`, the plan kind "accelerometer_misalignment", the
// JSON, the text and the report come from this file.
#include <nlohmann/json.hpp>

#include "inertest/core/citations.h"
#include "inertest/misalignment/accelerometer_misalignment.h"
#include "inertest/misalignment/misalignment_files.h"
#include "inertest/procedures/instrument_sensor.h"

namespace inertest {

ProcedureSpec accelerometer_misalignment_spec() {
  using Options = AccelerometerMisalignmentOptions;
  using Result = AccelerometerMisalignmentResult;
  return ProcedureDefinition<Options, Result>(
             "accelerometer_misalignment", "Accelerometer misalignment (four-position test)",
             "the misalignment paper, multi-position gravity test",
             "Accelerometer, input axis horizontal on a vertical face turned beta (4-position gravity test).\n"
             "POSITIONS has the header 'beta_deg,output' and optionally 'run'; any beta that separate the\n"
             "angles (the paper's 0, 90, 180, 270). Outputs (arcsec): delta_theta_y2, delta_theta_z2,\n"
             "misalignment (mean over runs with its standard error), by_run (the same per run, with run).\n"
             "Source: " +
                 std::string(citations::kMisalignmentPaper) + ".")
      .command_is("misalignment", "accelerometer")
      .chinese_title("加速度计失准角（四位置试验）")
      .report_method(
          "The accelerometer's input axis lies horizontal on a vertical face turned through β = 0°, 90°, 180°, 270°; "
          "the outputs give Δθy2 = (V(π) − V(0))/(2kI) and Δθz2 = (V(π/2) − V(3π/2))/(2kI).",
          "加速度计输入轴水平置于竖直基准面上，绕面法线转 β = 0°、90°、180°、270°；由输出求 Δθy2 = (V(π) − V(0))/(2kI)、"
          "Δθz2 = (V(π/2) − V(3π/2))/(2kI)。")
      .input(InputSpec("positions", "CSV of positions").read_from_file("POSITIONS", "file"))
      .parameter(ParameterSpec("scale_factor", "kI, output units per g")
                     .required_on_command_line()
                     .instrument_gives("nominal_scale_factor")
                     .instrument_gives_if(instrument_is_accelerometer),
                 &Options::scale_factor)
      .parameter(ParameterSpec("output_unit", "instrument output unit, e.g. V")
                     .instrument_gives("output_unit")
                     .instrument_gives_if(instrument_is_accelerometer),
                 &Options::output_unit)
      .figure_from({"delta_theta_y2", FieldRole::headline, "Δθy2 (input axis)", "Δθy2（输入轴）", "(V(π) − V(0))/(2kI)"},
                   [](const Result& r) { return r.combined.delta_theta_y2; })
      .figure_from({"delta_theta_z2", FieldRole::headline, "Δθz2 (input axis)", "Δθz2（输入轴）",
                    "(V(π/2) − V(3π/2))/(2kI)"},
                   [](const Result& r) { return r.combined.delta_theta_z2; })
      .figure_from({"misalignment", FieldRole::headline, "misalignment γ", "失准角 γ", "γ = √(Δθy2² + Δθz2²)"},
                   [](const Result& r) { return r.combined.misalignment; })
      .figure_from({"scale_factor", FieldRole::detail, "scale factor kI", "标度因数 kI", ""},
                   [](const Result& r) { return Figure{r.scale_factor, r.output_unit + "/g", std::nullopt}; })
      .field_from(FieldSpec{.name = "run_count", .role = FieldRole::detail, .label_en = "runs", .label_zh = "测试次数",
                            .equation = "", .axes = {}, .value_words = {}, .value = FieldValue::whole_number},
                  [](const Result& r) { return r.by_run.size(); })
      .field_from({"by_run", FieldRole::table, "solution of each run", "各次解", ""}, by_run_json)
      .field_from({"source", FieldRole::hidden, "source", "来源", ""},
                  [](const Result&) {
                    return std::string(citations::kMisalignmentPaper) +
                           ", accelerometer multi-position gravity test; least squares on V = V0 + kI (-dy0 - dy1 + "
                           "dz2 sin b - dy2 cos b)";
                  })
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &Result::warnings)
      .unit_of("delta_theta_y2", "arcsec")
      .unit_of("delta_theta_z2", "arcsec")
      .unit_of("misalignment", "arcsec")
      .unit_of("scale_factor", "{output_unit}/g")
      .compute([](const ProcedureCall& call, const Options& options) {
        Options located = options;
        located.source = call.files.at("positions");
        return accelerometer_misalignment(read_accelerometer_misalignment_positions(located.source), located);
      });
}

}  // namespace inertest

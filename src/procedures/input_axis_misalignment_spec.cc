// The input-axis misalignment procedure's one description (issue 22): the CLI command
// `inertest input-axis-misalignment`, the plan kind "input_axis_misalignment", its JSON and its text
// report are all generated from it.
#include "inertest/core/procedure_spec.h"
#include "inertest/procedures/input_axis_misalignment.h"
#include "inertest/procedures/instrument_sensor.h"

namespace inertest {
namespace {

// A four-position figure: null (left out) with two positions.
nlohmann::json optional_figure(const std::optional<Figure>& figure) { return figure ? nlohmann::json(*figure) : nlohmann::json(); }

}  // namespace

ProcedureSpec input_axis_misalignment_spec() {
  using Result = InputAxisMisalignmentResult;
  return ProcedureDefinition<InputAxisMisalignmentOptions, Result>(
             "input_axis_misalignment", "Input-axis misalignment", "GJB 2426A-2004 5.15, eqs. (47)-(50)",
             "The angle alpha of the IRA out of the plane normal to the table axis, IRA perpendicular to the\n"
             "table axis. POSITIONS has the header 'position,output_positive,output_negative': positions 1, 2\n"
             "(ox, then oy along the table axis) and optionally 3, 4 (the same turned 180 deg about IRA), each\n"
             "with the mean output over whole turns at +rate and -rate.\n"
             "delta_j = (F(j+) - F(j-))/(2 K rate), K in output per deg/s (the rate converted); two positions:\n"
             "alpha = asin(sqrt(delta1^2 + delta2^2)); four: the mounting error cancels,\n"
             "alpha = asin(sqrt(((delta1 - delta3)/2)^2 + ((delta2 - delta4)/2)^2)).")
      .chinese_title("输入轴失准角")
      .input(InputSpec("positions", "the mean outputs at +rate and -rate per position (position,output_positive,output_negative)")
                 .read_from_file("POSITIONS", "file"))
      .parameter(ParameterSpec("scale_factor", "K")
                     .unit_is("output units per deg/s")
                     .required_on_command_line()
                     .instrument_gives("nominal_scale_factor")
                     .instrument_gives_if(instrument_is_gyro),
                 &InputAxisMisalignmentOptions::scale_factor)
      .parameter(ParameterSpec("rate", "table rate magnitude, rate unit").required_on_command_line(),
                 &InputAxisMisalignmentOptions::rate)
      .parameter(ParameterSpec("rate_unit", "unit of the rate"),
                 &InputAxisMisalignmentOptions::rate_unit)
      .parameter(ParameterSpec("output_unit", "instrument output unit").instrument_gives("output_unit", true),
                 &InputAxisMisalignmentOptions::output_unit)
      .field({"misalignment", FieldRole::headline, "misalignment alpha", "输入轴失准角", "GJB 2426A-2004 eqs. (49)-(50)"},
             &Result::misalignment)
      .field({"misalignment_deg", FieldRole::detail, "misalignment alpha (deg)", "输入轴失准角 (°)", "eq. (49)"},
             &Result::misalignment_deg)
      .field({"deltas", FieldRole::table, "delta per position", "各位置偏角", "eqs. (47)-(48)"}, &Result::deltas)
      .field_from({"misalignment_toward_ox", FieldRole::detail, "IA tilt toward ox (about oy)", "IA 向 ox 偏斜（绕 oy）", "(delta1 - delta3)/2"},
                  [](const Result& r) { return optional_figure(r.misalignment_toward_ox); })
      .field_from({"misalignment_toward_oy", FieldRole::detail, "IA tilt toward oy (about ox)", "IA 向 oy 偏斜（绕 ox）", "(delta2 - delta4)/2"},
                  [](const Result& r) { return optional_figure(r.misalignment_toward_oy); })
      .field_from({"mounting_error", FieldRole::detail, "mounting error", "安装误差", "(delta1 + delta2 + delta3 + delta4)/4"},
                  [](const Result& r) { return optional_figure(r.mounting_error); })
      .field_from({"misalignment_eq50_as_printed", FieldRole::detail, "eq. (50) as printed", "式(50)原式", "eq. (50)"},
                  [](const Result& r) { return optional_figure(r.misalignment_eq50_as_printed); })
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &Result::warnings)
      .unit_of("misalignment", "arcsec")
      .unit_of("misalignment_deg", "deg")
      .unit_of("deltas", "arcsec")
      .unit_of("misalignment_toward_ox", "arcsec")
      .unit_of("misalignment_toward_oy", "arcsec")
      .unit_of("mounting_error", "arcsec")
      .unit_of("misalignment_eq50_as_printed", "arcsec")
      .compute([](const ProcedureCall& call, const InputAxisMisalignmentOptions& options) {
        return input_axis_misalignment(read_misalignment_positions(call.files.at("positions")), options);
      });
}

}  // namespace inertest

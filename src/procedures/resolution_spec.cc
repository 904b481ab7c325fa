// The resolution procedure's one description (issue 22): the CLI command `inertest resolution`, the
// plan kind "resolution", its JSON and its text report are all generated from it.
#include <nlohmann/json.hpp>

#include "inertest/procedures/resolution.h"
#include "inertest/procedures/instrument_sensor.h"
#include "procedures/fifty_percent_criterion.h"

namespace inertest {
namespace {

// Each direction's candidate and every increment with its eq. (18) test.
nlohmann::json branches_json(const ResolutionResult& result) {
  return criterion::branches_json(result.branches, [&](const ResolutionPoint& p) {
    return nlohmann::json{{"increment", Figure{p.increment_deg_h, "deg/h", std::nullopt}},
                          {"expected_output_increment", Figure{p.expected_increment, result.output_unit, std::nullopt}},
                          {"output_increment", Figure{p.output_increment, result.output_unit, std::nullopt}},
                          {"relative_error", p.relative_error},
                          {"satisfies", p.satisfies}};
  });
}

}  // namespace

ProcedureSpec resolution_spec() {
  return ProcedureDefinition<ResolutionOptions, ResolutionResult>(
             "resolution", "Resolution", "GJB 2426A-2004 5.11.4, eq. (18)",
             "50 % criterion of eq. 18, K in output units per deg/s.\n"
             "STEPS has the header 'base_rate,base_output,rate,output': one row per increment, the base rate\n"
             "(its sign gives the direction) and its mean output measured before the increment, then the\n"
             "rate with the increment and its mean output; rates in --rate-unit (default deg/s).")
      .chinese_title("分辨率")
      .input(InputSpec("steps", "CSV of increments").read_from_file("STEPS", "file"))
      .parameter(ParameterSpec("scale_factor", "K")
                     .unit_is("output units per deg/s")
                     .required_on_command_line()
                     .instrument_gives("nominal_scale_factor")
                     .instrument_gives_if(instrument_is_gyro),
                 &ResolutionOptions::scale_factor)
      .parameter(ParameterSpec("rate_unit", "unit of the rate columns"), &ResolutionOptions::rate_unit)
      .parameter(ParameterSpec("output_unit", "instrument output unit").instrument_gives("output_unit", true),
                 &ResolutionOptions::output_unit)
      .field({"resolution", FieldRole::headline, "resolution", "分辨率", "GJB 2426A-2004 5.11.3 f, eq. (18)"},
             &ResolutionResult::resolution)
      .field_from({"branches", FieldRole::table, "candidate per direction", "各方向候选值", "eq. (18)"},
                  branches_json)
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &ResolutionResult::warnings)
      .unit_of("resolution", "deg/h")
      .compute([](const ProcedureCall& call, const ResolutionOptions& options) {
        return resolution(read_resolution_steps(call.files.at("steps")), options);
      });
}

}  // namespace inertest

// The maximum input rate procedure's one description (issue 22): the CLI command
// `inertest maximum-input-rate`, the plan kind "maximum_input_rate", its JSON and its text report
// are all generated from it.
#include <nlohmann/json.hpp>

#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/maximum_input_rate.h"

namespace inertest {
namespace {

// Every range R tried, ascending, with its nonlinearity Kn(R) and whether it meets the requirement.
nlohmann::json ranges_json(const MaximumInputRateResult& result) {
  nlohmann::json ranges = nlohmann::json::array();
  for (const auto& r : result.ranges) {
    ranges.push_back({{"rate", Figure{r.rate, result.rate_unit, std::nullopt}},
                      {"nonlinearity", Figure{r.nonlinearity, "ppm", std::nullopt}},
                      {"meets_requirement", r.meets_requirement}});
  }
  return ranges;
}

}  // namespace

ProcedureSpec maximum_input_rate_spec() {
  return ProcedureDefinition<MaximumInputRateOptions, MaximumInputRateResult>(
             "maximum_input_rate", "Maximum input rate", "GJB 2426A-2004 5.9 (with 5.8.1-5.8.2, eqs. 1-9)",
             "the largest tested rate R such that the scale-factor nonlinearity (eqs. 1-9)\n"
             "over the points with |rate| <= R meets --nonlinearity-limit (smaller ranges that miss it are a warning).\n"
             "POINTS has the header 'rate,output', as for 'inertest scale-factor', tested beyond the expected\n"
             "maximum.")
      .chinese_title("最大输入角速度")
      .input(InputSpec("points", "CSV of test points (rate,output)").read_from_file("POINTS", "file"))
      .parameter(ParameterSpec("nonlinearity_limit", "the nonlinearity requirement")
                     .unit_is("ppm")
                     .required_on_command_line()
                     .plan_key_is("nonlinearity_limit_ppm"),
                 &MaximumInputRateOptions::nonlinearity_limit_ppm)
      .parameter(ParameterSpec("rate_unit", "unit of the rates"), &MaximumInputRateOptions::scale_factor,
                 &ScaleFactorOptions::rate_unit)
      .parameter(ParameterSpec("output_unit", "instrument output unit").instrument_gives("output_unit", true),
                 &MaximumInputRateOptions::scale_factor, &ScaleFactorOptions::output_unit)
      .field({"maximum_input_rate", FieldRole::headline, "maximum input rate", "最大输入角速度", "GJB 2426A-2004 5.9"},
             &MaximumInputRateResult::maximum_input_rate)
      .field({"nonlinearity", FieldRole::detail, "nonlinearity there", "该处标度因数非线性度", "eq. (9)"},
             &MaximumInputRateResult::nonlinearity)
      .field({"nonlinearity_limit", FieldRole::detail, "nonlinearity requirement", "非线性度要求", ""},
             &MaximumInputRateResult::nonlinearity_limit)
      .field({"scale_factor", FieldRole::detail, "scale factor there", "该处标度因数", "eq. (5)"},
             &MaximumInputRateResult::scale_factor)
      .field_from({"ranges", FieldRole::table, "nonlinearity per range", "各范围非线性度", "eqs. (1)-(9)"}, ranges_json)
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &MaximumInputRateResult::warnings)
      .unit_of("maximum_input_rate", "{rate_unit}")
      .unit_of("nonlinearity", "ppm")
      .unit_of("nonlinearity_limit", "ppm")
      .unit_of("scale_factor", "{output_unit}/({rate_unit})")
      .compute([](const ProcedureCall& call, const MaximumInputRateOptions& options) {
        return maximum_input_rate(read_scale_factor_points(call.files.at("points")), options);
      });
}

}  // namespace inertest

// The scale factor repeatability procedure's one description (issue 22): the CLI command
// `inertest scale-factor-repeatability`, the plan kind "scale_factor_repeatability", its JSON and
// its text report are all generated from it.
#include <nlohmann/json.hpp>

#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/scale_factor_repeatability.h"

namespace inertest {

ProcedureSpec scale_factor_repeatability_spec() {
  return ProcedureDefinition<ScaleFactorRepeatabilityOptions, ScaleFactorRepeatabilityResult>(
             "scale_factor_repeatability", "Scale factor repeatability", "GJB 2426A-2004 5.8.4, eq. (12)",
             "Kr over Q runs of the scale-factor test.\n"
             "Each FILE is one run's test points, header 'rate,output', as for 'inertest scale-factor'.\n"
             "GJB 2426A 5.8.4.3 asks for Q >= 6 runs: fewer is an error unless --minimum-runs is lowered\n"
             "(to no less than 2), and the result then carries a warning.")
      .chinese_title("标度因数重复性")
      .input(InputSpec("runs", "one CSV of test points (rate,output) per run").runs_in_files("FILE", "files"))
      .parameter(ParameterSpec("minimum_runs", "fewest runs accepted (5.8.4.3 asks for 6)"),
                 &ScaleFactorRepeatabilityOptions::minimum_runs)
      .parameter(ParameterSpec("rate_unit", "unit of the rates"), &ScaleFactorRepeatabilityOptions::scale_factor,
                 &ScaleFactorOptions::rate_unit)
      .parameter(ParameterSpec("output_unit", "instrument output unit").instrument_gives("output_unit", true),
                 &ScaleFactorRepeatabilityOptions::scale_factor, &ScaleFactorOptions::output_unit)
      .field({"scale_factor_repeatability", FieldRole::headline, "repeatability Kr", "标度因数重复性", "eq. (12)"},
             &ScaleFactorRepeatabilityResult::scale_factor_repeatability)
      .field({"mean_scale_factor", FieldRole::detail, "mean scale factor", "标度因数平均值", "eq. (12)"},
             &ScaleFactorRepeatabilityResult::mean_scale_factor)
      .field_from({"runs", FieldRole::detail, "runs Q", "测试次数", ""},
                  [](const ScaleFactorRepeatabilityResult& result) { return result.run_scale_factors.size(); })
      .field({"run_scale_factors", FieldRole::table, "scale factor of each run", "各次标度因数", "eqs. (1)-(6)"},
             &ScaleFactorRepeatabilityResult::run_scale_factors)
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &ScaleFactorRepeatabilityResult::warnings)
      .checked_by([](const ProcedureCall& call, const ScaleFactorRepeatabilityOptions& options) {
        options.validate();
        options.check_run_count(call.runs.at("runs").size());
      })
      .unit_of("scale_factor_repeatability", "ppm")
      .unit_of("mean_scale_factor", "{output_unit}/({rate_unit})")
      .unit_of("run_scale_factors", "{output_unit}/({rate_unit})")
      .compute([](const ProcedureCall& call, const ScaleFactorRepeatabilityOptions& options) {
        std::vector<std::vector<ScaleFactorPoint>> runs;
        for (const RunInput& run : call.runs.at("runs")) runs.push_back(read_scale_factor_points(run.file));
        return scale_factor_repeatability(runs, options);
      });
}

}  // namespace inertest

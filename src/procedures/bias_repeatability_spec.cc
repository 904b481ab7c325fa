// The bias repeatability procedure's one description (issue 22): the CLI command
// `inertest bias-repeatability`, the plan kind "bias_repeatability", its JSON and its text report
// are all generated from it.
#include <nlohmann/json.hpp>

#include "inertest/procedures/bias.h"
#include "inertest/procedures/bias_repeatability.h"

namespace inertest {

ProcedureSpec bias_repeatability_spec() {
  ProcedureDefinition<BiasOptions, BiasRepeatabilityResult> definition(
      "bias_repeatability", "Bias repeatability", "GJB 2426A-2004 5.12.3, eq. (21)",
      "the standard deviation (Q-1) of the biases of Q runs (Q >= 6 asked\n"
      "for; at least 2 needed), each bias = mean output / K in deg/h (eq. 19).\n"
      "Each FILE is one run's output record (one column, or --column; or binary with --format).");
  definition.chinese_title("零偏重复性")
      .input(InputSpec("runs", "one output record per run")
                 .runs_in_files("FILE", "files")
                 .output_records()
                 .at_least(2, "GJB 2426A 5.12.3 asks for 6 or more"));
  return bias_conversion_parameters(definition, +[](BiasOptions& options) -> BiasOptions& { return options; })
      .field({"bias_repeatability", FieldRole::headline, "bias repeatability Br", "零偏重复性", "eq. (21)"},
             &BiasRepeatabilityResult::bias_repeatability)
      .field({"mean_bias", FieldRole::detail, "mean bias", "零偏平均值", "eq. (21)"}, &BiasRepeatabilityResult::mean_bias)
      .field_from({"runs", FieldRole::detail, "runs Q", "测试次数", ""},
                  [](const BiasRepeatabilityResult& result) { return result.run_biases.size(); })
      .field_from({"run_biases", FieldRole::table, "bias of each run", "各次零偏", "eq. (19)"},
                  [](const BiasRepeatabilityResult& result) {
                    nlohmann::json runs = nlohmann::json::array();
                    for (double b : result.run_biases) runs.push_back(Figure{b, "deg/h", std::nullopt});
                    return runs;
                  })
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &BiasRepeatabilityResult::warnings)
      .checked_by([](const ProcedureCall& call, const BiasOptions& options) {
        check_bias_conversion(call, options, "bias repeatability");
      })
      .unit_of("bias_repeatability", "deg/h")
      .unit_of("mean_bias", "deg/h")
      .unit_of("run_biases", "deg/h")
      .compute([](const ProcedureCall& call, const BiasOptions& options) {
        std::vector<double> biases;
        for (const RunInput& run : call.runs.at("runs")) biases.push_back(bias_deg_h(read_bias_record(call, run.file, options), options));
        return bias_repeatability(biases);
      });
}

}  // namespace inertest

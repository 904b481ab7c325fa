// The bias temperature sensitivity procedure's one description (issue 22): the CLI command
// `inertest bias-temperature`, the plan kind "bias_temperature", its JSON and its text report are all
// generated from it.
#include <nlohmann/json.hpp>

#include "inertest/procedures/bias.h"
#include "inertest/procedures/bias_temperature_sensitivity.h"

namespace inertest {
namespace {

// What the spec binds: eq. (22)'s options and eq. (19)'s conversion of each run's record.
struct Options {
  BiasTemperatureOptions temperature;
  BiasOptions conversion;
};

}  // namespace

ProcedureSpec bias_temperature_spec() {
  ProcedureDefinition<Options, BiasTemperatureSensitivityResult> definition(
      "bias_temperature", "Bias temperature sensitivity", "GJB 2426A-2004 5.12.4, eq. (22)",
      "max |B0i - B0m| / |Ti - Tm| over the runs, B0m the bias at room temperature Tm (the run at\n"
      "--room-temperature, or the first --run, which must lie in 15-35 degC, 4.1.1.1). Each --run is\n"
      "TEMPERATURE_DEGC:FILE, FILE one run's output record (one column, or --column; or binary with\n"
      "--format); bias = mean output / K in deg/h (eq. 19).");
  definition.json_procedure_is("bias_temperature_sensitivity")
      .chinese_title("零偏温度灵敏度")
      .report_method(
          "The bias of eq. (19) is measured at room temperature and, after the soak, at each test temperature; the sensitivity is the largest ratio of the change of bias from room temperature to the change of temperature, |B0i − B0m| / |Ti − Tm| (eq. (22)).",
          "按式(19)分别求出室温及各试验温度点（保温使陀螺仪达到热平衡后）的零偏，按式(22)取零偏相对室温零偏的变化量与温度变化量之比的最大值为零偏温度灵敏度。")
      .input(InputSpec("runs", "one output record per temperature")
                 .numbered_runs("temperature_degC", "25:run_25C.txt")
                 .output_records()
                 .at_least(2, "room temperature and one other"))
      .parameter(ParameterSpec("room_temperature_degC", "the room temperature Tm (default: the first run's)")
                     .unit_is("degC")
                     .command_line_name_is("room-temperature"),
                 [](Options& options, const nlohmann::json& value) {
                   options.temperature.room_temperature_degC = value.get<double>();
                 });
  return bias_conversion_parameters(definition, +[](Options& options) -> BiasOptions& { return options.conversion; })
      .field({"bias_temperature_sensitivity", FieldRole::headline, "temperature sensitivity Bt", "零偏温度灵敏度",
              "eq. (22)"},
             &BiasTemperatureSensitivityResult::bias_temperature_sensitivity)
      .field({"room_temperature", FieldRole::detail, "room temperature Tm", "室温", ""},
             &BiasTemperatureSensitivityResult::room_temperature)
      .field({"room_temperature_bias", FieldRole::detail, "bias at room temperature B0m", "室温零偏", "eq. (19)"},
             &BiasTemperatureSensitivityResult::room_temperature_bias)
      .field({"worst_temperature", FieldRole::detail, "worst temperature", "最大灵敏度对应温度", ""},
             &BiasTemperatureSensitivityResult::worst_temperature)
      .field_from({"runs", FieldRole::table, "bias at each temperature", "各温度零偏", "eqs. (19), (22)"},
                  [](const BiasTemperatureSensitivityResult& result) {
                    nlohmann::json table = nlohmann::json::array();
                    for (std::size_t i = 0; i < result.runs.size(); ++i) {
                      table.push_back({{"temperature", Figure{result.runs[i].temperature_degC, "degC", std::nullopt}},
                                       {"bias", Figure{result.runs[i].bias_deg_h, "deg/h", std::nullopt}},
                                       {"sensitivity", Figure{result.sensitivities[i], "deg/h/degC", std::nullopt}}});
                    }
                    return table;
                  })
      .checked_by([](const ProcedureCall& call, const Options& options) {
        check_bias_conversion(call, options.conversion, "bias temperature sensitivity");
      })
      .unit_of("bias_temperature_sensitivity", "deg/h/degC")
      .unit_of("room_temperature", "degC")
      .unit_of("room_temperature_bias", "deg/h")
      .unit_of("worst_temperature", "degC")
      .compute([](const ProcedureCall& call, const Options& options) {
        std::vector<TemperatureRunBias> runs;
        for (const RunInput& run : call.runs.at("runs")) {
          runs.push_back({run.number, bias_deg_h(read_bias_record(call, run.file, options.conversion), options.conversion)});
        }
        return bias_temperature_sensitivity(runs, options.temperature);
      });
}

}  // namespace inertest

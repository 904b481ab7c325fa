// The scale factor temperature sensitivity procedure's one description (issue 22): the CLI command
// `inertest scale-factor-temperature`, the plan kind "scale_factor_temperature", its JSON and its
// text report are all generated from it.
#include <algorithm>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/scale_factor_temperature_sensitivity.h"

namespace inertest {

ProcedureSpec scale_factor_temperature_spec() {
  using Options = ScaleFactorTemperatureOptions;
  using Result = ScaleFactorTemperatureResult;
  return ProcedureDefinition<Options, Result>(
             "scale_factor_temperature", "Scale factor temperature sensitivity", "GJB 2426A-2004 5.8.5, eq. (13)",
             "Kt = max over the test temperatures Ti of |(Ki - Km)/(Km (Ti - Tm))|, in ppm/degC.\n"
             "RUNS is a CSV with the header 'temperature_degC,file': one scale-factor test per temperature\n"
             "(each file has the header 'rate,output', paths relative to RUNS). The room-temperature run\n"
             "Tm is the first row, or the row at --reference-temperature.")
      .chinese_title("标度因数温度灵敏度")
      .json_procedure_is("scale_factor_temperature_sensitivity")
      .input(InputSpec("runs", "one CSV of test points (rate,output) per temperature")
                 .numbered_runs("temperature_degC", "20:sf_20C.csv")
                 .listed_on_command_line("RUNS")
                 .at_least(2, "room temperature and a test temperature"))
      .parameter(ParameterSpec("reference_temperature", "room temperature Tm (default: the first run)")
                     .unit_is("degC")
                     .plan_key_is("reference_temperature_degC"),
                 [](Options& options, const nlohmann::json& value) {
                   options.reference_temperature_degC = value.get<double>();
                 })
      .parameter(ParameterSpec("rate_unit", "unit of the rates"), &Options::scale_factor,
                 &ScaleFactorOptions::rate_unit)
      .parameter(ParameterSpec("output_unit", "instrument output unit").instrument_gives("output_unit", true),
                 &Options::scale_factor, &ScaleFactorOptions::output_unit)
      .field({"scale_factor_temperature_sensitivity", FieldRole::headline, "sensitivity Kt", "标度因数温度灵敏度",
              "eq. (13)"},
             &Result::scale_factor_temperature_sensitivity)
      .field_from({"worst_temperature", FieldRole::detail, "at temperature", "最大值所在温度", "eq. (13)"},
                  [](const Result& result) {
                    return Figure{result.worst_temperature_degC, "degC", std::nullopt};
                  })
      .field({"reference_scale_factor", FieldRole::detail, "reference Km", "室温标度因数", "5.8.5.3 a"},
             &Result::reference_scale_factor)
      .field({"reference_temperature", FieldRole::detail, "reference temperature Tm", "室温", "5.8.5.3 a"},
             &Result::reference_temperature)
      .field_from(
          {"test_temperatures", FieldRole::table, "K and sensitivity at each temperature", "各温度点", "eq. (13)"},
          [](const Result& result) {
            nlohmann::json points = nlohmann::json::array();
            for (const auto& p : result.test_temperatures) {
              points.push_back({{"temperature", Figure{p.temperature_degC, "degC", std::nullopt}},
                                {"scale_factor", p.scale_factor},
                                {"sensitivity", p.sensitivity}});
            }
            return points;
          })
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &Result::warnings)
      .checked_by([](const ProcedureCall& call, const Options& options) {
        options.validate();
        const auto& runs = call.runs.at("runs");
        if (options.reference_temperature_degC && std::none_of(runs.begin(), runs.end(), [&](const RunInput& run) {
              return run.number == *options.reference_temperature_degC;
            })) {
          throw ParameterError("reference_temperature",
                               fmt::format("reference temperature {} degC matches no run's temperature_degC",
                                           *options.reference_temperature_degC));
        }
      })
      .unit_of("scale_factor_temperature_sensitivity", "ppm/degC")
      .unit_of("worst_temperature", "degC")
      .unit_of("reference_temperature", "degC")
      .unit_of("reference_scale_factor", "{output_unit}/({rate_unit})")
      .compute([](const ProcedureCall& call, const Options& options) {
        std::vector<TemperatureRun> runs;
        for (const RunInput& run : call.runs.at("runs"))
          runs.push_back({run.number, read_scale_factor_points(run.file)});
        return scale_factor_temperature_sensitivity(runs, options);
      });
}

}  // namespace inertest

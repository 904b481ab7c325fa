// Applying exported temperature-model coefficients to a record (issue 20), declared once (issue 22):
// `inertest temperature-apply RECORD --coefficients FILE`, the plan kind "temperature_apply", its
// JSON, text, report and Python function come from this file. The compensation is the model
// equation of IEEE Std 952-1997 (Annex B) with the coefficients that temperature-model --export wrote.
#include <nlohmann/json.hpp>

#include "inertest/procedures/temperature_model.h"
#include "procedures/temperature_model_internal.h"

namespace inertest {

ProcedureSpec temperature_apply_spec() {
  using Options = TemperatureModelOptions;
  using Result = TemperatureApplyResult;
  ProcedureDefinition<Options, Result> definition(
      "temperature_apply", "Temperature compensation", "IEEE Std 952-1997 Annex B (model equation)",
      "subtracts the bias model that `inertest temperature-model --export` wrote (--coefficients FILE,\n"
      ".json or .csv) from a record's bias output/K, with dT/dt and the heating/cooling legs found as the model\n"
      "was fitted, and shows the residual: its bias stability beside the raw one over the same windows.\n"
      "RECORD is a text record with a time column, an output column and the exported sensor's column\n"
      "(or --temperature-column).");
  definition.chinese_title("温度补偿")
      .report_method(
          "The bias model fitted from a chamber ramp is subtracted from a record's bias at the temperature and the "
          "temperature rate of each interval; the bias stability after compensation is shown beside the raw one.",
          "用温箱试验拟合的零偏温度模型，按各区间的温度与温度变化率从记录的零偏中扣除；给出补偿后与补偿前同窗口的零偏稳定性。")
      .example({"examples/temperature_model/ramp.csv", "--coefficients", "examples/temperature_model/coefficients.json",
                "--scale-factor", "36000", "--interval", "60", "--stability-window", "600"})
      .input(InputSpec("record", "record: time, output and temperature columns")
                 .read_from_file("RECORD", "file")
                 .holds_raw_samples())
      .input(InputSpec("coefficients", "the exported coefficients (.json or .csv)").read_from_file("--coefficients", "coefficients"));
  thermal::record_parameters(definition);
  definition.parameter(ParameterSpec("temperature_column", "the temperature column (default: the exported sensor)"),
                       &Options::temperature_columns);
  thermal::stability_fields(definition);
  return definition
      .field({"residual_rms", FieldRole::detail, "residual rms of the interval means", "区间平均残差均方根", ""},
             &Result::residual_rms)
      .field({"residual_mean", FieldRole::detail, "mean residual", "残差均值", ""}, &Result::residual_mean)
      .field({"temperature_sensor", FieldRole::detail, "compensation sensor", "补偿用温度传感器", ""}, &Result::sensor)
      .field_from({"residual_series", FieldRole::curve, "residual after compensation", "补偿后残差", "",
                   {"time", "residual"}},
                  [](const Result& result) {
                    nlohmann::json points = nlohmann::json::array();
                    const std::size_t step = (result.intervals.size() + 199) / 200;
                    for (std::size_t i = 0; i < result.intervals.size(); i += step) {
                      const ThermalInterval& interval = result.intervals[i];
                      points.push_back({{"time", Figure{interval.time_s, "s", std::nullopt}},
                                        {"residual", Figure{interval.bias_deg_h - interval.model_deg_h, "deg/h", std::nullopt}}});
                    }
                    return points;
                  })
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &Result::warnings)
      .unit_of("residual_rms", "deg/h")
      .unit_of("residual_mean", "deg/h")
      .compute([](const ProcedureCall& call, const Options& options) {
        const ThermalCompensation compensation = read_thermal_compensation(call.files.at("coefficients"));
        const std::string sensor = options.temperature_columns.empty() ? compensation.sensor : options.temperature_columns.front();
        const ThermalRecord record = thermal::read_record(call, options, {sensor});
        // A complaint about the record (too short for its windows) names it: of the two files the
        // command reads, the coefficients' errors already name theirs.
        return with_file_context(call.files.at("record"),
                                 [&] { return apply_thermal_compensation(record, compensation, options); });
      });
}

}  // namespace inertest

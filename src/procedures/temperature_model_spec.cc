// The temperature model's one description (issue 20, in the spec shape of issue 22): the CLI command
// `inertest temperature-model`, the plan kind "temperature_model", its JSON, text, report and Python
// function all come from this file. The method is in procedures/temperature_model.h.
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inertest/io/atomic_write.h"
#include "inertest/procedures/temperature_model.h"
#include "procedures/temperature_model_internal.h"

namespace inertest {
namespace {

using Options = TemperatureModelOptions;
using Result = TemperatureModelResult;

// At most this many points per curve: every k-th averaging interval.
constexpr std::size_t kCurvePoints = 200;

// The points of a curve: `members` of every k-th interval. "heating", "cooling" and "soak" are the
// bias on that leg only (absent on the others), so that the report draws the legs in their colours.
nlohmann::json curve(const Result& result, const std::vector<std::string>& members) {
  nlohmann::json points = nlohmann::json::array();
  const std::size_t step = (result.intervals.size() + kCurvePoints - 1) / kCurvePoints;
  for (std::size_t i = 0; i < result.intervals.size(); i += step) {
    const ThermalInterval& interval = result.intervals[i];
    const std::string leg = interval.leg > 0 ? "heating" : interval.leg < 0 ? "cooling" : "soak";
    const std::map<std::string, Figure> values = {
        {"time", {interval.time_s, "s", std::nullopt}},
        {"temperature", {interval.temperature_degC, "degC", std::nullopt}},
        {"bias", {interval.bias_deg_h, "deg/h", std::nullopt}},
        {leg, {interval.bias_deg_h, "deg/h", std::nullopt}},
        {"model", {interval.model_deg_h, "deg/h", std::nullopt}},
        {"residual", {interval.bias_deg_h - interval.model_deg_h, "deg/h", std::nullopt}}};
    nlohmann::json point = nlohmann::json::object();
    for (const std::string& member : members) {
      if (values.contains(member)) point[member] = values.at(member);
    }
    points.push_back(std::move(point));
  }
  return points;
}

}  // namespace

ProcedureSpec temperature_model_spec() {
  ProcedureDefinition<Options, Result> definition(
      "temperature_model", "Bias temperature model", "IEEE Std 952-1997 Annex B (model equation)",
      "fits B = D_0 + sum_k D_Tk dT^k + D_dT T' + D_TdT dT T' + D_H h (dT = T - T_ref, T' = dT/dt, h = +1/2\n"
      "heating, -1/2 cooling, 0 soak) to a chamber ramp record by least squares with covariance; the\n"
      "order by k-fold cross-validation on contiguous blocks (one-standard-error rule); T' by local\n"
      "linear regression over --rate-window; the residual bias stability after compensation beside the\n"
      "raw one, over the same windows. RECORD is a text record with a time column (s), an output column\n"
      "and one or more temperature columns (degC, or K where the name says so: coil_K, coil [K]; the first\n"
      "compensates, the others are compared).\n"
      "--export FILE writes the coefficients: FILE.json {\"model\", \"sensor\", \"order\", \"scale_factor\",\n"
      "\"reference_temperature_degC\", \"rate_window_s\", \"soak_rate_degC_per_min\", \"coefficients\": {name: {value,\n"
      "unit, uncertainty}}} or FILE.csv 'name,value,unit,uncertainty' (rows sensor, order, reference_temperature,\n"
      "rate_window, soak_rate, scale_factor, then D_0, D_T, D_T2, ..., D_dT, D_TdT, D_H); `inertest temperature-apply`\n"
      "applies them, and warns when its K is not the scale_factor they were fitted with.");
  definition.chinese_title("零偏温度模型")
      .report_method(
          "A chamber record with soaks and ramps, heating and cooling, is averaged into short intervals; the "
          "temperature rate of each interval is the slope of a local linear regression over a window; the bias is "
          "fitted by least squares as a polynomial in temperature (order chosen by cross-validation on contiguous "
          "blocks) plus terms in the temperature rate, temperature times rate (Shupe effect) and a hysteresis "
          "between heating and cooling, as in the model equation of IEEE Std 952-1997. The bias stability after "
          "compensation is shown beside the raw one, and GJB 2426A's one-number sensitivity (eq. 22) beside the "
          "model.",
          "温箱记录包含保温段与升降温段；记录按短区间平均，各区间的温度变化率取窗口内局部线性回归的斜率；零偏按最小二乘拟合为"
          "温度多项式（阶次由连续分块交叉验证确定）加温度变化率项、温度与变化率乘积项（Shupe 效应）和升降温迟滞项"
          "（IEEE Std 952-1997 模型方程）。给出补偿后与补偿前同窗口的零偏稳定性，并与 GJB 2426A 式 (22) 的零偏温度灵敏度并列。")
      .example({"examples/temperature_model/ramp.csv", "--temperature-column", "coil", "--temperature-column",
                "chamber", "--scale-factor", "36000", "--interval", "60", "--stability-window", "600",
                "--rate-window", "600"})
      .input(InputSpec("record", "chamber ramp record: time, output and temperature columns")
                 .read_from_file("RECORD", "file")
                 .holds_raw_samples());
  thermal::record_parameters(definition);
  definition
      .parameter(ParameterSpec("temperature_column", "a temperature column (degC) by name or 1-based index; repeat for "
                                                     "several sensors")
                     .required_on_command_line(),
                 &Options::temperature_columns)
      .parameter(ParameterSpec("reference_temperature", "T_ref of the coefficients").unit_is("degC"),
                 &Options::reference_temperature_degC)
      .parameter(ParameterSpec("maximum_order", "highest polynomial order in temperature tried"), &Options::maximum_order)
      .parameter(ParameterSpec("folds", "contiguous blocks of the cross-validation"), &Options::folds)
      .parameter(ParameterSpec("rate_window_s", "local linear regression window of dT/dt").unit_is("s").command_line_name_is("rate-window"),
                 &Options::rate_window_s)
      .parameter(ParameterSpec("soak_rate", "|dT/dt| below which the chamber soaks (neither heating nor cooling)")
                     .unit_is("degC/min"),
                 &Options::soak_rate_degC_per_min)
      .parameter(ParameterSpec("rate_terms", "fit the terms in dT/dt (false: a model in T alone)")
                     .command_line_flag("no-rate-terms", false),
                 &Options::rate_terms)
      .parameter(ParameterSpec("export", "write the coefficients to FILE (.json or .csv; in a plan a relative FILE is beside "
                                           "results.json)").writes_file(), &Options::export_file);
  thermal::stability_fields(definition);
  definition
      .field_from({"bias_coefficients", FieldRole::detail, "model coefficients", "模型系数", "IEEE Std 952-1997 Annex B"},
                  [](const Result& result) {
                    nlohmann::json coefficients = nlohmann::json::object();
                    for (const auto& c : result.coefficients) coefficients[c.name] = c.value;
                    return coefficients;
                  })
      .field({"order", FieldRole::detail, "polynomial order in temperature", "温度多项式阶次", "cross-validation"},
             &Result::order)
      .field({"temperature_sensor", FieldRole::detail, "compensation sensor", "补偿用温度传感器", ""}, &Result::sensor)
      .field({"reference_temperature", FieldRole::detail, "reference temperature T_ref", "参考温度", ""},
             &Result::reference_temperature)
      .field({"residual_rms", FieldRole::detail, "residual rms of the interval means", "区间平均残差均方根", ""},
             &Result::residual_rms)
      .field({"bias_temperature_sensitivity", FieldRole::detail, "GJB one-number sensitivity from the model",
              "零偏温度灵敏度（GJB 单值）", "GJB 2426A-2004 5.12.4, eq. (22)"},
             &Result::bias_temperature_sensitivity)
      .field_from({"order_selection", FieldRole::table, "cross-validation by order", "各阶交叉验证", "ESL 7.10"},
                  [](const Result& result) {
                    nlohmann::json rows = nlohmann::json::array();
                    for (const auto& s : result.order_scores) {
                      rows.push_back({{"order", s.order},
                                      {"cv_rms", Figure{s.cv_rms_deg_h, "deg/h", std::nullopt}},
                                      {"cv_mean_square_standard_error", Figure{s.cv_standard_error, "deg^2/h^2", std::nullopt}}});
                    }
                    return rows;
                  })
      .field_from({"sensors", FieldRole::table, "fit with each sensor", "各温度传感器拟合", ""},
                  [](const Result& result) {
                    nlohmann::json rows = nlohmann::json::array();
                    for (const auto& s : result.sensors) {
                      rows.push_back({{"sensor", s.sensor}, {"order", s.order}, {"residual_rms", s.residual_rms}});
                    }
                    return rows;
                  })
      .field_from({"bias_against_temperature", FieldRole::curve, "bias against temperature", "零偏-温度曲线",
                   "IEEE Std 952-1997 Annex B", {"temperature", "heating", "cooling", "soak", "model"}},
                  [](const Result& result) { return curve(result, {"temperature", "heating", "cooling", "soak", "model"}); })
      .field_from({"residual_series", FieldRole::curve, "residual after compensation", "补偿后残差", "",
                   {"time", "residual"}},
                  [](const Result& result) { return curve(result, {"time", "residual"}); })
      .field_from({"time_series", FieldRole::curve, "bias and temperature profile", "零偏与温度剖面", "",
                   {"time", "bias", "model", "temperature"}},
                  [](const Result& result) { return curve(result, {"time", "bias", "model", "temperature"}); })
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &Result::warnings);
  definition
      .unit_of("reference_temperature", "degC")
      .unit_of("residual_rms", "deg/h")
      .unit_of("bias_temperature_sensitivity", "deg/h/degC");
  return definition.compute([](const ProcedureCall& call, const Options& options) {
    const ThermalRecord record = thermal::read_record(call, options, options.temperature_columns);
    Result result = temperature_model(record, options);
    if (!options.export_file.empty()) {
      const std::string path = call.output_path(options.export_file);
      write_file_atomically(path, thermal_coefficients_text(result, options, path));
    }
    return result;
  });
}

}  // namespace inertest

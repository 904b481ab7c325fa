// The bias procedure's one description (issue 22): the CLI command `inertest bias`, the plan kind
// "bias", its JSON and its text report are all generated from it.
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/io/time_stamps.h"
#include "inertest/procedures/bias.h"
#include "inertest/procedures/earth_rate_parameters.h"

namespace inertest {
namespace {

// The smoothed records behind eq. (20), for the report's plot; one beyond kMaxSmoothedPoints means
// (a 1 s smoothing of a day-long record) is left out to keep results.json small.
nlohmann::json smoothed_record_json(const BiasResult& result) {
  constexpr std::size_t kMaxSmoothedPoints = 20000;
  nlohmann::json smoothed = nlohmann::json::array();
  for (const auto& s : result.bias_stability) {
    if (s.smoothed.size() > kMaxSmoothedPoints) continue;
    smoothed.push_back({{"smoothing_s", s.smoothing_s}, {"unit", "deg/h"}, {"values", s.smoothed}});
  }
  return smoothed;
}

// The random-walk figures come together, when the record supports the random walk coefficient.
nlohmann::json normalised_curve_json(const BiasResult& result) {
  if (!result.random_walk_coefficient) return nullptr;
  nlohmann::json curve = nlohmann::json::array();
  for (const auto& p : result.normalised_stability_curve) {
    curve.push_back({{"tau_s", p.tau_s}, {"value", p.stability}, {"unit", "deg/h"}});
  }
  return curve;
}

// One row per smoothing time asked for, in the order asked: a time the record cannot support keeps
// its row, {"smoothing_s", "value": null, "unit", "measured": false, "reason"}, so that a plan's
// limit on "/bias_stability/N" names the N-th time asked for (a left-out 3000 s had shifted the
// 10 s value under the limit meant for 3000 s) and is judged "not measured".
nlohmann::json bias_stability_json(const BiasResult& result) {
  nlohmann::json stability = nlohmann::json::array();
  auto left_out = result.smoothing_left_out.begin();
  auto measured = result.bias_stability.begin();
  const std::size_t rows = result.bias_stability.size() + result.smoothing_left_out.size();
  for (std::size_t place = 0; place < rows; ++place) {
    if (left_out != result.smoothing_left_out.end() && left_out->place == place) {
      stability.push_back({{"smoothing_s", left_out->smoothing_s}, {"value", nullptr}, {"unit", "deg/h"},
                           {"measured", false}, {"reason", left_out->reason}});
      ++left_out;
    } else {
      stability.push_back({{"smoothing_s", measured->smoothing_s}, {"value", measured->value.value},
                           {"unit", measured->value.unit}});
      ++measured;
    }
  }
  return stability;
}

}  // namespace

ProcedureSpec bias_spec() {
  ProcedureDefinition<BiasOptions, BiasResult> definition(
      "bias", "Bias", "GJB 2426A-2004 5.12.1-5.12.2, 5.12.5.4.1, eqs. (19), (20), (23), (24)",
      "bias (eq. 19), bias stability (eq. 20) and random walk coefficient by the\n"
      "normalisation method (eqs. 23-24) from one record of the gyro at rest.\n"
      "FILE holds the instrument output, one sample (the mean output rate) per sampling interval: a text\n"
      "record (one column, or --column NAME|INDEX) or a binary record (--format f64|f32|...). K is in\n"
      "output units per deg/s; bias = mean output / K in deg/h. Bias stability: standard deviation (n-1)\n"
      "of the means of consecutive whole windows of each smoothing time, in deg/h. Random walk coefficient in\n"
      "deg/sqrt(h) = Bs(1 s)[deg/h] / 60. Earth rate is not removed unless --remove-earth-rate.\n"
      "A smoothing time the record cannot support (longer than half of it, not whole samples) and a random\n"
      "walk coefficient from under 2 s or below 1 Hz are left out with a warning; the bias is always given.");
  definition.chinese_title("零偏")
      .report_method(
          "The bias is the mean output over the record; the bias stability is the standard deviation of the output averaged over the smoothing time, expressed as an input rate.",
          "零偏为记录时间内输出的平均值折算成输入角速度；零偏稳定性为按平滑时间平均后输出的标准偏差折算成输入角速度。")
      .input(InputSpec("record", "instrument output record").read_from_file("FILE", "file").output_records().samples_at_least(2))
      .parameter(ParameterSpec("smoothing_s", "smoothing times for the bias stability")
                     .unit_is("s")
                     .command_line_name_is("smoothing"),
                 &BiasOptions::smoothing_s);
  bias_conversion_parameters(definition, +[](BiasOptions& options) -> BiasOptions& { return options; });
  earth_rate_parameters(definition, &BiasOptions::remove_earth_rate);
  return definition
      .field({"bias", FieldRole::headline, "bias B0", "零偏", "eq. (19)"}, &BiasResult::bias)
      .field_from(FieldSpec{"bias_stability", FieldRole::table, "bias stability", "零偏稳定性", "eq. (20)"}.rows_follow("smoothing_s"),
                  bias_stability_json)
      .field_from({"noise_equivalent_rate", FieldRole::detail, "noise equivalent rate Bs(1 s)", "噪声等效角速率",
                   "eq. (24)"},
                  [](const BiasResult& result) {
                    return result.random_walk_coefficient ? nlohmann::json(*result.noise_equivalent_rate) : nullptr;
                  })
      .field({"random_walk_coefficient", FieldRole::headline, "random walk coefficient", "随机游走系数", "eq. (24)"},
             &BiasResult::random_walk_coefficient)
      .field_from({"normalised_stability_curve", FieldRole::curve, "normalised bias stability Bs(tau)",
                   "归一化零偏稳定性", "eq. (23)", {"tau_s", "value"}},
                  normalised_curve_json)
      .field({"earth_rate_removed", FieldRole::detail, "Earth rate removed", "扣除的地球自转角速率", ""},
             &BiasResult::earth_rate_removed)
      .field({"samples", FieldRole::detail, "samples", "采样点数", ""}, &BiasResult::samples)
      .field({"duration", FieldRole::detail, "record duration", "记录时长", ""}, &BiasResult::duration)
      .field_from({"smoothed_record", FieldRole::curve, "smoothed records", "平滑后记录", "eq. (20)"},
                  smoothed_record_json)
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &BiasResult::warnings)
      .checked_by([](const ProcedureCall& call, BiasOptions options) {
        check_bias_conversion(call, options, "bias");
        // A rate not given comes from the record when it is read (compute): the rest is checked now.
        if (options.sample_rate_hz == 0.0) options.sample_rate_hz = 1.0;
        options.validate();
      })
      .unit_of("bias", "deg/h")
      .unit_of("bias_stability", "deg/h")
      .unit_of("noise_equivalent_rate", "deg/h")
      .unit_of("random_walk_coefficient", "deg/sqrt(h)")
      .unit_of("duration", "s")
      .compute([](const ProcedureCall& call, BiasOptions options) {
        const std::string& file = call.files.at("record");
        options.sample_rate_hz = call.record_sample_rate(file, options.sample_rate_hz);  // given or stored
        const std::vector<double> record = read_bias_record(call, file, options);
        // Eq. (20)'s windows are counted in samples at the rate: a gap in a text record's own stamps,
        // or a rate that changes, would put unequal times in them (a bias alone, by its mean, needs no
        // such check: the repeatability and temperature runs are not held to it).
        check_time_column_span(file, record.size());
        return bias(record, options);
      });
}

}  // namespace inertest

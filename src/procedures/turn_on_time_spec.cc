// The turn-on time and warm-up time procedures' one description (issue 22): power_on_time_spec makes
// both kinds (warm_up_time_spec.cc names the second); the CLI commands `inertest turn-on-time` and
// `inertest warm-up-time`, the plan kinds, their JSON and their text reports are generated from it.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/io/output_record.h"
#include "inertest/procedures/earth_rate_parameters.h"
#include "inertest/procedures/turn_on_time.h"
#include "inertest/procedures/instrument_sensor.h"

namespace inertest {

ProcedureSpec power_on_time_spec(bool warm_up) {
  const std::string kind = warm_up ? "warm_up_time" : "turn_on_time";
  ProcedureDefinition<TurnOnTimeOptions, TurnOnTimeResult> definition(
      kind, warm_up ? "Warm-up time" : "Turn-on time",
      warm_up ? "GJB 2426A-2004 5.6.4 (as 5.5.4)" : "GJB 2426A-2004 5.5.4",
      "from records that start at power-on, the time until the indicated rate\n"
      "(F - F0)/K (at rate less the Earth rate too) stays within the band to the end of the record; the\n"
      "largest over the runs.\n"
      "Each --run is INPUT_RATE_DEG_S:FILE (0 for a run at rest). Record layout: a text record with a time\n"
      "column (s since power-on; --time-column, default the first) and an output column (--column, default\n"
      "the second); or, with --rate HZ, the output column alone (text or binary --format), sample i (from 0)\n"
      "at time (i + 1)/HZ. Bands: at rate |rate error| <= --rate-band x |input rate| (a fraction, e.g.\n"
      "0.001); at rest |indicated rate| <= --rest-band deg/h. --smoothing S averages into S-second windows\n"
      "(0, S], (S, 2S], ... from power-on (a sample's time ends its interval; each window stamped at its\n"
      "end) before the test.");
  definition.chinese_title(warm_up ? "预热时间" : "启动时间")
      .report_method(
          fmt::format("From power-on, the output with the calibrated zero removed (and, at rate, the Earth rate) is "
                      "followed until the indicated rate stays within the required rate error (at rate) or bias (at "
                      "rest); the {} is the longest such interval over the runs.",
                      warm_up ? "warm-up time" : "turn-on time"),
          fmt::format("{}从加电开始，输出中扣除事先标定的零位（速率试验中还扣除地球速率），确定每次从加电到陀螺仪指示"
                      "满足速率误差要求（速率试验）或达到要求零偏值（位置试验）的时间，取其最大值为{}。",
                      warm_up ? "带温控的陀螺仪" : "", warm_up ? "预热时间" : "启动时间"))
      .input(InputSpec("runs", "one record per power-on run")
                 .numbered_runs("input_rate_deg_s", "100:power_on_100dps.txt")
                 .number_defaults_to(0.0)
                 .timed_records()
                 .samples_at_least(2)
                 .at_least(1, "a run at rate or at rest"))
      .parameter(ParameterSpec("scale_factor", "K")
                     .unit_is("output units per deg/s")
                     .required_on_command_line()
                     .instrument_gives("nominal_scale_factor")
                     .instrument_gives_if(instrument_is_gyro),
                 &TurnOnTimeOptions::scale_factor)
      .parameter(ParameterSpec("zero_output", "calibrated zero output F0 (pulse/s for a pulse counter)").unit_is("output units").command_line_name_is("zero"),
                 &TurnOnTimeOptions::zero_output)
      .parameter(ParameterSpec("rate_band", "allowed rate error relative to the input rate").needed_for("runs at rate"),
                 &TurnOnTimeOptions::rate_band)
      .parameter(ParameterSpec("rest_band_deg_h", "allowed indicated rate at rest")
                     .unit_is("deg/h")
                     .command_line_name_is("rest-band")
                     .needed_for("runs at rest"),
                 &TurnOnTimeOptions::rest_band_deg_h)
      .parameter(ParameterSpec("smoothing_s", "averaging window before the test (0: none)").unit_is("s").command_line_name_is("smoothing"),
                 &TurnOnTimeOptions::smoothing_s)
      .parameter(ParameterSpec("output_unit", "instrument output unit (pulse: counts per sample interval, read as pulse/s)")
                     .instrument_gives("output_unit", true),
                 &TurnOnTimeOptions::output_unit);
  earth_rate_parameters(definition, &TurnOnTimeOptions::earth_rate);
  return definition
      .field({kind, FieldRole::headline, warm_up ? "warm-up time" : "turn-on time", warm_up ? "预热时间" : "启动时间",
              warm_up ? "GJB 2426A-2004 5.6.4" : "GJB 2426A-2004 5.5.4"},
             &TurnOnTimeResult::time)
      .field({"longest_run", FieldRole::detail, "longest run", "最长的一次", ""}, &TurnOnTimeResult::longest_run)
      .field_from({"runs", FieldRole::table, "time of each run", "各次时间", ""},
                  [](const TurnOnTimeResult& result) {
                    nlohmann::json runs = nlohmann::json::array();
                    for (const auto& r : result.runs) {
                      runs.push_back({{"name", r.name},
                                      {"input_rate", Figure{r.input_rate_deg_s, "deg/s", std::nullopt}},
                                      {"time", r.time}});
                    }
                    return runs;
                  })
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &TurnOnTimeResult::warnings)
      .checked_by([](const ProcedureCall& call, const TurnOnTimeOptions& options) {
        options.validate();
        for (const RunInput& run : call.runs.at("runs")) {
          if (run.number == 0.0 && options.rest_band_deg_h <= 0.0) {
            throw Error("a run at rest needs rest_band_deg_h (--rest-band)");
          }
          if (run.number != 0.0 && options.rate_band <= 0.0) throw Error("a run at rate needs rate_band (--rate-band)");
        }
      })
      .unit_of(kind, "s")
      .compute([warm_up](const ProcedureCall& call, TurnOnTimeOptions options) {
        options.warm_up = warm_up;
        std::vector<PowerOnRun> runs;
        for (const RunInput& run : call.runs.at("runs")) {
          require_raw_output(call, run.file, options.output_unit, "the indicated rate is (F - F0)/K");
          TimedRecord record = call.read_timed_record(run.file);
          runs.push_back({run.name, run.number, std::move(record.time_s), std::move(record.output)});
        }
        return turn_on_time(runs, options);
      });
}

ProcedureSpec turn_on_time_spec() { return power_on_time_spec(false); }

}  // namespace inertest

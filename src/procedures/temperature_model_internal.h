// The steps that temperature_model and temperature_apply share (procedures/temperature_model.h):
// averaging intervals, their smoothed temperature rate and leg, the compensated bias, the bias
// record parameters and the stability figures. Private to src/procedures.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "inertest/core/procedure_spec.h"
#include "inertest/procedures/temperature_model.h"
#include "inertest/procedures/instrument_sensor.h"

namespace inertest::thermal {

struct Interval {
  double time_s = 0.0;
  double bias_deg_h = 0.0;                 // output / K, GJB 2426A eq. (19)
  std::vector<double> temperature_degC;    // one per sensor
  double rate_degC_per_min = 0.0;          // of the sensor set_rates was given
  int leg = 0;                             // +1 heating, −1 cooling, 0 soak
};

// A logger's gaps in the record (io/time_stamps.h), said and not refused: the intervals about one hold
// fewer samples, or are missing, and each is still one interval mean of the fit. None without a gap.
std::optional<std::string> gap_warning(const ThermalRecord& record, double interval_s);

// Step 1: means over consecutive intervals of interval_s from the record's first time.
std::vector<Interval> intervals_of(const ThermalRecord& record, double interval_s, double scale_factor);

// Step 2: Ṫ of `sensor` by local linear regression over rate_window_s, and the leg by the soak rate.
void set_rates(std::vector<Interval>& intervals, std::size_t sensor, double rate_window_s, double soak_rate_degC_per_min);

// The bias less the model's (deg/h).
double compensated_bias(const Interval& interval, std::size_t sensor, std::span<const ThermalCoefficient> coefficients,
                        double reference_temperature_degC);

// The chamber record of `call` (read_thermal_record) with the columns of `options` and the given
// temperature columns. Its outputs in an output unit that counts pulses per sample interval
// (call.pulse_counts) are made pulse/s at the record's mean sample rate, which K, output per deg/s,
// divides (GJB 2426A-2004 eq. (19)): counts per 1 s interval taken as pulse/s gave the right bias
// only by the accident of a 1 Hz log.
ThermalRecord read_record(const ProcedureCall& call, const TemperatureModelOptions& options,
                          const std::vector<std::string>& temperature_columns);

// The parameters of a spec reading a chamber record: K and the output unit, the time and output
// columns, the averaging interval and the stability window (temperature_model_spec.cc,
// temperature_apply_spec.cc). The record input holds raw samples (InputSpec::holds_raw_samples).
template <typename Result>
void record_parameters(ProcedureDefinition<TemperatureModelOptions, Result>& definition) {
  using Options = TemperatureModelOptions;
  definition
      .parameter(ParameterSpec("scale_factor", "K: bias = output / K")
                     .unit_is("output units per deg/s")
                     .required_on_command_line()
                     .instrument_gives("nominal_scale_factor")
                     .instrument_gives_if(instrument_is_gyro),
                 &Options::scale_factor)
      .parameter(ParameterSpec("output_unit", "instrument output unit (pulse: counts per sample interval, read as "
                                              "pulse/s at the record's mean sample rate)")
                     .instrument_gives("output_unit", true),
                 &Options::output_unit)
      .parameter(ParameterSpec("time_column", "the time column (s) by name or 1-based index"), &Options::time_column)
      .parameter(ParameterSpec("output_column", "the output column by name or 1-based index"), &Options::output_column)
      .parameter(ParameterSpec("interval_s", "averaging interval").unit_is("s").command_line_name_is("interval"),
                 &Options::interval_s)
      .parameter(ParameterSpec("stability_window_s", "window of the bias stabilities")
                     .unit_is("s")
                     .command_line_name_is("stability-window"),
                 &Options::stability_window_s);
}

// The headline figures of both: the bias stability (GJB 2426A-2004 eq. (20)) after compensation and,
// over the same windows, before it.
template <typename Result>
void stability_fields(ProcedureDefinition<TemperatureModelOptions, Result>& definition) {
  definition
      .field({"residual_bias_stability", FieldRole::headline, "bias stability after compensation", "补偿后零偏稳定性",
              "GJB 2426A-2004 eq. (20)"},
             &Result::residual_bias_stability)
      .field({"raw_bias_stability", FieldRole::headline, "bias stability before compensation", "补偿前零偏稳定性",
              "GJB 2426A-2004 eq. (20)"},
             &Result::raw_bias_stability)
      .unit_of("residual_bias_stability", "deg/h")
      .unit_of("raw_bias_stability", "deg/h");
}

}  // namespace inertest::thermal

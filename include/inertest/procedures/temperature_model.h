// Bias over temperature and its rate of change, from a chamber ramp record (soaks and ramps, heating
// and cooling), with the coefficients that compensate it (issue 20).
//
// GJB 2426A-2004 5.12.4 (eq. 22) gives one number, the bias temperature sensitivity from soaks. IEEE
// Std 952-1997's model equation (Annex B; clause 8.1.3) carries temperature and temperature-gradient
// terms, D = D_0 + D_T ΔT + D_dT dT/dt + ..., and a fiber coil's bias depends on dT/dt through the
// Shupe effect (Shupe, Appl. Opt. 19 (1980) 654) and on whether the coil is heating or cooling. The
// model fitted here, with ΔT = T − T_ref and Ṫ = dT/dt:
//   B(T, Ṫ) = D_0 + Σ_{k=1..n} D_Tk ΔT^k + D_dT Ṫ + D_TdT ΔT Ṫ + D_H h,
// h = +1/2 while heating, −1/2 while cooling, 0 in a soak (|Ṫ| below a threshold): D_H is the
// hysteresis, the heating leg minus the cooling leg at the same temperature and rate.
//
// Method, every step stated:
// 1. The record is averaged over consecutive intervals (interval_s): times, bias = output/K and
//    each temperature sensor; a sensor quantised to q reads to better than q within an interval.
// 2. Ṫ of each interval: the slope of a local linear regression of the interval temperatures over a
//    centred window of rate_window_s (Cleveland 1979, degree 1), so that the derivative of a
//    quantised sensor does not dominate: its noise falls as W^(-3/2).
// 3. Least squares (numerics/least_squares.h) with covariance s²(AᵀA)⁻¹, in a centred and scaled
//    temperature (conditioning), mapped exactly to physical coefficients about T_ref.
// 4. The order n ≤ maximum_order by k-fold cross-validation on contiguous blocks of the record
//    (neighbouring intervals share correlated noise and would favour over-fitting if split): the
//    lowest order whose prediction mean square is within one standard error of the least
//    (Hastie, Tibshirani & Friedman, Elements of Statistical Learning, 2nd ed., 7.10).
// 5. The first sensor is the compensation sensor (the one the navigation system reads); the model
//    is fitted to each other sensor too, for comparison, with a warning when one fits better.
// 6. Bias stability (GJB 2426A eq. 20: the standard deviation of window means) of the raw bias and
//    of the residual after compensation, over the same windows of stability_window_s.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"

namespace inertest {

// A chamber record: time (s), instrument output and one or more temperature sensors (degC).
struct ThermalRecord {
  std::vector<double> time_s;
  std::vector<double> output;
  std::vector<std::string> sensor_names;
  std::vector<std::vector<double>> temperature_degC;  // one per sensor, each as long as time_s
};

// The options of temperature_model and of temperature_apply (which uses K, the columns, the interval
// and the stability window).
struct TemperatureModelOptions {
  double scale_factor = 0.0;                 // K, output units per deg/s (bias = output / K)
  std::string output_unit;                   // the instrument's; pulse: counts per sample interval
  std::string time_column = "time";          // the record's columns, by header name or 1-based index
  std::string output_column = "output";
  std::vector<std::string> temperature_columns;  // temperature_apply: empty takes the exported sensor
  std::string export_file;  // the command writes the coefficients there (.json, .csv); "" : none
  double reference_temperature_degC = 20.0;  // T_ref of the physical coefficients
  std::size_t maximum_order = 4;             // highest order of the polynomial in ΔT tried
  std::size_t folds = 10;                    // contiguous blocks of the cross-validation
  double interval_s = 10.0;                  // averaging interval of step 1
  double rate_window_s = 120.0;              // local linear regression window of Ṫ
  double soak_rate_degC_per_min = 0.05;      // |Ṫ| below this: a soak, neither heating nor cooling
  double stability_window_s = 100.0;         // window of the bias stabilities
  bool rate_terms = true;                    // fit D_dT and D_TdT (false: a model in T alone)

  // Throws Error naming the option that is out of range.
  void validate() const;
};

// Coefficient names: "D_0", "D_T", "D_T2", ... "D_dT", "D_TdT", "D_H"; units deg/h, deg/h/degC^k,
// deg/h/(degC/min), deg/h/degC/(degC/min), deg/h.
struct ThermalCoefficient {
  std::string name;
  Figure value;
};

struct OrderScore {
  std::size_t order = 0;
  double cv_rms_deg_h = 0.0;       // root mean square of the held-out prediction errors
  double cv_standard_error = 0.0;  // of the mean square, across folds (deg/h)^2
};

struct SensorFit {
  std::string sensor;
  std::size_t order = 0;
  Figure residual_rms;  // deg/h, interval means
};

// One averaging interval (step 1), with the model and the leg.
struct ThermalInterval {
  double time_s = 0.0;
  double temperature_degC = 0.0;  // the compensation sensor
  double rate_degC_per_min = 0.0;
  int leg = 0;  // +1 heating, −1 cooling, 0 soak
  double bias_deg_h = 0.0;
  double model_deg_h = 0.0;
};

struct TemperatureModelResult {
  std::string sensor;  // the compensation sensor
  std::size_t order = 0;
  Figure reference_temperature;
  std::vector<ThermalCoefficient> coefficients;
  Figure residual_bias_stability;  // after compensation, deg/h
  Figure raw_bias_stability;       // before, the same windows
  Figure residual_rms;             // of the interval means, deg/h
  // GJB 2426A-2004 5.12.4 eq. (22) from the static part of the model, at the record's lowest and
  // highest temperature against T_ref: max |B(T) − B(T_ref)| / |T − T_ref|. When cross-validation
  // chooses order 0 (the dependence not resolved, not absent): the order-1 fit's |D_T| with its
  // 1-sigma, and a warning.
  Figure bias_temperature_sensitivity;
  std::vector<OrderScore> order_scores;
  std::vector<SensorFit> sensors;
  std::vector<ThermalInterval> intervals;
  std::vector<std::string> warnings;
};

// Throws Error when the record is too short for the intervals and windows, the sensors' lengths
// differ from the time's, the compensation sensor reads one temperature throughout, or the design cannot identify a term (the least-squares rank check names
// it: a record without ramps cannot give D_dT).
TemperatureModelResult temperature_model(const ThermalRecord& record, const TemperatureModelOptions& options);

// The model's bias (deg/h) at temperature T and rate Ṫ (degC/min) on leg h (+1, −1, 0).
double thermal_bias_deg_h(std::span<const ThermalCoefficient> coefficients, double reference_temperature_degC,
                          double temperature_degC, double rate_degC_per_min, int leg);

// Ṫ (degC/min) of each sample: the slope of a local linear regression over a centred window of
// window_s (shortened at the ends); times increase.
std::vector<double> smoothed_rate_degC_per_min(std::span<const double> time_s, std::span<const double> temperature_degC,
                                               double window_s);

// The exported compensation coefficients (--export), documented in the spec's help:
// JSON {"model": "inertest temperature model", "sensor", "order", "scale_factor" (K, output units per
// deg/s, which temperature-apply's is held against), "reference_temperature_degC",
// "rate_window_s", "soak_rate_degC_per_min", "coefficients": {name: {value, unit, uncertainty}}};
// CSV with the header 'name,value,unit,uncertainty' and the settings (sensor, order, ...) as rows whose
// unit column names them. By the file's extension (.json or .csv).
std::string thermal_coefficients_text(const TemperatureModelResult& result, const TemperatureModelOptions& options,
                                      const std::string& path);

struct ThermalCompensation {
  std::string sensor;
  double reference_temperature_degC = 20.0;
  double rate_window_s = 120.0;
  double soak_rate_degC_per_min = 0.05;
  // The K the bias was read with (output units per deg/s); none in files written before exports stated it.
  std::optional<double> scale_factor;
  std::vector<ThermalCoefficient> coefficients;
};

// Reads an exported file (either form); throws Error naming the file (and the line of the CSV form,
// the key of the JSON form) when it is not one: a coefficient of no term of the model, a unit that
// does not convert to the model's (the values come back in deg/h, deg/h/degC^k, deg/h/(degC/min),
// deg/h/degC/(degC/min), whatever unit the file gives), a term missing (D_0, D_T ... D_Tn for the
// order n the file states or, in a file without one, the highest power given; D_dT and D_TdT together).
ThermalCompensation read_thermal_compensation(const std::string& path);

struct TemperatureApplyResult {
  std::string sensor;
  Figure raw_bias_stability;       // deg/h, GJB 2426A eq. (20)
  Figure residual_bias_stability;  // after compensation, the same windows
  Figure residual_rms;             // of the compensated interval means about their mean, deg/h
  Figure residual_mean;            // deg/h
  std::vector<ThermalInterval> intervals;
  std::vector<std::string> warnings;
};

// Applies exported coefficients to a record of the compensation's sensor (record.temperature_degC[0]):
// intervals, Ṫ and legs as the model was fitted (the compensation's rate window and soak rate),
// then bias minus model. Throws Error as temperature_model does for a short record.
TemperatureApplyResult apply_thermal_compensation(const ThermalRecord& record, const ThermalCompensation& compensation,
                                                  const TemperatureModelOptions& options);

// Reads a chamber record: a text record with a time column, an output column and the named
// temperature columns (by header name or 1-based index); times increase strictly (an Error names
// the line otherwise).
ThermalRecord read_thermal_record(const std::string& path, const std::string& time_column,
                                  const std::string& output_column, const std::vector<std::string>& temperature_columns);

ProcedureSpec temperature_model_spec();
ProcedureSpec temperature_apply_spec();

}  // namespace inertest

// Bias, bias stability and random walk coefficient (normalisation method) from one record of a
// gyro at rest: GJB 2426A-2004 5.12.1 eq. (19), 5.12.2 eq. (20), 5.12.5.4.1 eqs. (23)-(24);
// IEEE Std 952-1997 clause 13 (A.11).
//
//   B0 = F̄ / K                                                                            (19)
//
// Input: the instrument output, one sample per sampling interval at sample_rate_hz, each the mean
// output RATE over its interval (5.12.1.3 b records the accumulation over the interval; divided by
// the interval's length it is that rate). K is the scale factor in output units per deg/s, so F̄/K
// is in deg/s and is reported in deg/h. With input_in_deg_h the record already holds rate in deg/h
// and K is not used.
//
// The bias is given for any record of two samples or more. Every bias stability and the random
// walk coefficient that the record supports are given too; a smoothing time longer than half the
// record or not a whole number of samples, and a random walk coefficient from a record under 2 s or
// sampled below 1 Hz, are left out with a warning saying why.
//
// Earth rate: the standard's bias is the mean indicated rate, which includes whatever Earth rate
// the IRA sees (5.12.1.3 points the IRA east-west, where that is zero). It is not removed unless
// remove_earth_rate gives the site latitude and the IRA orientation; then Ωe along the IRA
// (earth_rate.h) is subtracted from the bias. Stability and random walk are unaffected.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/procedures/earth_rate.h"
#include "inertest/procedures/random_walk_normalisation.h"
#include "inertest/procedures/instrument_sensor.h"

namespace inertest {

struct BiasOptions {
  double sample_rate_hz = 0.0;  // must be positive
  double scale_factor = 0.0;    // K, output units per deg/s; nonzero unless input_in_deg_h
  bool input_in_deg_h = false;  // the record holds rate in deg/h already
  std::string output_unit = "1";  // for the report only
  std::vector<double> smoothing_s{1.0, 10.0, 100.0};  // bias stability smoothing times, s
  bool random_walk = true;  // compute the random walk coefficient (given for at least 2 s at >= 1 Hz)
  std::optional<AxisOrientation> remove_earth_rate;

  // Throws Error for a non-positive rate, a zero or non-finite scale factor, an empty or
  // non-positive smoothing time, or an invalid orientation.
  void validate() const;
  // What eq. (19) alone needs (bias_deg_h): a nonzero, finite scale factor unless input_in_deg_h,
  // and a valid orientation; no sample rate. Throws Error.
  void validate_conversion() const;
  // deg/h per output unit: 3600 / K (or 1 with input_in_deg_h).
  double deg_h_per_output() const;
};

struct BiasStabilityFigure {
  double smoothing_s = 0.0;
  std::size_t windows = 0;  // n of eq. (20)
  Figure value;             // deg/h
  std::vector<double> smoothed;  // F_i/K in deg/h (Earth rate removed if asked): the smoothed record
};

// A smoothing time the record cannot support (longer than half of it, not whole samples): its place
// among the smoothing times asked for, so that the JSON keeps a row at that place (a plan's limit on
// "/bias_stability/1" names the second smoothing time asked for, measured or not).
struct SmoothingLeftOut {
  std::size_t place = 0;
  double smoothing_s = 0.0;
  std::string reason;
};

struct BiasResult {
  Figure bias;                                    // eq. (19), deg/h (Earth rate removed if asked)
  std::vector<BiasStabilityFigure> bias_stability;  // eq. (20), one per smoothing time the record supports
  std::vector<SmoothingLeftOut> smoothing_left_out;  // the others, also in warnings
  std::optional<Figure> noise_equivalent_rate;      // NER = Bs(1 s), deg/h, when the record supports it
  std::optional<Figure> random_walk_coefficient;    // eq. (24), deg/sqrt(h), when the record supports it
  std::vector<NormalisedStabilityPoint> normalised_stability_curve;  // Bs(τ) in deg/h, eq. (23)
  std::optional<Figure> earth_rate_removed;       // deg/h, when removed
  std::size_t samples = 0;
  Figure duration;                                // s
  std::vector<std::string> warnings;              // e.g. a constant record (stuck channel)
};

// Throws Error for invalid options or fewer than two samples. Smoothing times and a random walk
// coefficient the record cannot support are warnings (see above), and so are all of them on a
// constant record (a stuck channel: a spread of 0 is no measurement, and passed every limit).
BiasResult bias(std::span<const double> output, const BiasOptions& options);

// The procedure's spec (src/procedures/bias_spec.cc): CLI, plan step, JSON and text.
ProcedureSpec bias_spec();

// The check, before any record is read, of a spec whose records eq. (19) converts (`procedure`: bias,
// its repeatability or temperature sensitivity): the scale factor given unless the records hold deg/h,
// and not given when they do (it would go unused), then validate_conversion(). Throws Error.
void check_bias_conversion(const ProcedureCall& call, const BiasOptions& options, const std::string& procedure);

// One run's record for eq. (19), read as `call` says it is stored. Records said to hold rates
// (input = "deg/h") are converted to deg/h from the rate unit the file stores (an HDF5 or TDMS
// channel's: deg/s, not a bias 3600 times too small); another stored unit (V) is an Error naming
// both. Records of the output, which K divides, must not store a rate or an acceleration: an Error
// (dividing a record's deg/s by K gave 0.025 deg/h for a bias of 898 deg/h). Throws Error naming
// the file.
std::vector<double> read_bias_record(const ProcedureCall& call, const std::string& file, const BiasOptions& options);

// Declares eq. (19)'s conversion on `definition`, alike for bias, its repeatability and temperature
// sensitivity: sample_rate_hz (--rate), output_unit (pulse: counts per sample interval, read as
// pulse/s at that rate or the record's), scale_factor (K; a plan without it takes [instrument]
// nominal_scale_factor, unless its records hold deg/h, which take neither K nor the output unit) and
// input ("output", or "deg/h" for records in deg/h already: the flag --input-deg-h), stored in the
// BiasOptions that `conversion` gives of the procedure's Options.
template <typename Options, typename Result>
ProcedureDefinition<Options, Result>& bias_conversion_parameters(ProcedureDefinition<Options, Result>& definition,
                                                                  BiasOptions& (*conversion)(Options&)) {
  return definition
      .parameter(ParameterSpec("sample_rate_hz", "sample rate (default: the rate the record stores, an HDF5 or TDMS "
                                                 "channel's; one that contradicts it is an error)")
                     .unit_is("Hz")
                     .command_line_name_is("rate")
                     .instrument_gives("sample_rate_hz"),
                 [conversion](Options& options, const nlohmann::json& value) {
                   // Given, it must be a rate: 0 stands for none given (the record's, at compute).
                   const double rate = value.get<double>();
                   if (!(rate > 0.0) || !std::isfinite(rate)) {
                     throw ParameterError("sample_rate_hz", fmt::format("sample_rate_hz must be positive, got {} Hz", rate));
                   }
                   conversion(options).sample_rate_hz = rate;
                 })
      .parameter(ParameterSpec("output_unit", "instrument output unit, for the report (pulse: counts per sample "
                                              "interval, read as pulse/s)")
                     .text()
                     .instrument_gives("output_unit", true)
                     .instrument_gives_when("input", "output"),
                 [conversion](Options& options, const nlohmann::json& value) {
                   conversion(options).output_unit = value.get<std::string>();
                 })
      .parameter(ParameterSpec("scale_factor", "K")
                     .unit_is("output units per deg/s")
                     .instrument_gives("nominal_scale_factor")
                     .instrument_gives_when("input", "output")
                     .instrument_gives_if(instrument_is_gyro),
                 [conversion](Options& options, const nlohmann::json& value) {
                   conversion(options).scale_factor = value.get<double>();
                 })
      .parameter(ParameterSpec("input", "what the records hold: the output, or rate in deg/h (or in the rate unit the file stores)")
                     .one_of({"output", "deg/h"})
                     .command_line_flag("input-deg-h", "deg/h"),
                 "output",
                 [conversion](Options& options, const nlohmann::json& value) {
                   conversion(options).input_in_deg_h = value == "deg/h";
                 });
}

// Eq. (19) alone, in deg/h (Earth rate removed if asked): the bias of one run, as bias
// repeatability and temperature sensitivity use it. Mean by compensated sum. Needs no sample rate
// or smoothing times; throws Error for an empty record or a zero scale factor.
double bias_deg_h(std::span<const double> output, const BiasOptions& options);

}  // namespace inertest

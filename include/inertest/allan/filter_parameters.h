// The noise parameters a navigation filter takes, from the Allan fit of each channel (issue 19):
// continuous-time densities in SI units, the bias instability with a first-order Gauss-Markov
// equivalent, and the discrete-time values at the record's rate; written as a Kalibr imu.yaml, a
// MATLAB script of gyroparams/accelparams, a gnss-ins-sim IMU error dictionary, or JSON.
//
// From the fit of GJB 2426A eq. (30) (IEEE Std 952-1997 C.1, noise_terms.h):
//   white-noise density   = N (angle/velocity random walk): sigma(tau) = N / sqrt(tau), so a
//                           white rate of one-sided PSD S1 has N = sqrt(S1 / 2), in rad/s/sqrt(Hz)
//                           or m/s^2/sqrt(Hz) (Kalibr's *_noise_density, MATLAB's NoiseDensity);
//   random-walk density   = K (rate/acceleration random walk): sigma(tau) = K sqrt(tau / 3), in
//                           rad/s^2/sqrt(Hz) or m/s^3/sqrt(Hz) (Kalibr's *_random_walk, MATLAB's
//                           RandomWalk, whose (rad/s)*sqrt(Hz) is the same unit);
//   bias instability      = B, in rad/s or m/s^2: flicker noise, which no finite filter state is;
//                           its first-order Gauss-Markov equivalent b' = -b / T + w has the
//                           correlation time T = tau_min / 1.89 and the sigma whose Allan maximum is
//                           the flicker floor 0.664 B (the Allan variance of the process is
//                           sigma^2 (2x - 3 + 4 e^-x - e^-2x) / x^2, x = tau / T, largest at x = 1.89:
//                           El-Sheimy, Hou and Niu, IEEE Trans. Instrum. Meas. 57(1), 2008, eq. 23),
//                           tau_min the tau where the fitted curve is least.
// Discrete-time at the sample interval dt: white sigma_d = N / sqrt(dt), random-walk step
// sigma_w = K sqrt(dt), Gauss-Markov phi = exp(-dt / T) and driving sigma sigma_GM sqrt(1 - phi^2).
// A term the fit did not identify is given by its upper bound, and the files say so.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "inertest/allan/allan_channels.h"
#include "inertest/allan/noise_terms.h"

namespace inertest {

struct NoiseDensity {
  double value = 0.0;        // SI
  double uncertainty = 0.0;  // 1-sigma; 0 for an upper bound
  bool identified = true;    // false: value is the fit's upper bound
  // False for an estimate within 2 sigma of zero (NoiseTerms::significant): the value is still the
  // estimate, and upper_bound its 2-sigma bound (SI), which the files' comments give beside it.
  bool significant = true;
  double upper_bound = 0.0;
};

struct SensorNoiseParameters {
  std::string channel;
  SensorKind kind = SensorKind::kGyro;  // kGyro or kAccelerometer
  double sample_rate_hz = 0.0;
  NoiseDensity white_noise_density;     // N: rad/s/sqrt(Hz) or m/s^2/sqrt(Hz)
  NoiseDensity random_walk_density;     // K: rad/s^2/sqrt(Hz) or m/s^3/sqrt(Hz)
  NoiseDensity bias_instability;        // B: rad/s or m/s^2
  double gauss_markov_sigma = 0.0;                 // rad/s or m/s^2
  double gauss_markov_correlation_time_s = 0.0;
  // False when the fitted sigma^2(tau) is least at an end of the curve's taus: at the longest (no
  // turn up within the record: flicker without a rate random walk, or a fit with K held at zero) or
  // the shortest (a rate random walk alone). The correlation time is then that tau over 1.8926, a
  // figure of the record, not of the instrument (six channels of one flicker noise gave 185 to
  // 3463 s, unsaid).
  bool gauss_markov_identified = true;
  double discrete_white_sigma = 0.0;               // per sample: rad/s or m/s^2
  double discrete_random_walk_sigma = 0.0;         // per sample step: rad/s or m/s^2
  double discrete_gauss_markov_phi = 0.0;
  double discrete_gauss_markov_sigma = 0.0;        // driving noise per sample
};

// One entry per channel, in order. Throws Error for a channel whose unit is neither an angular rate
// nor a specific force, or whose noise terms were not fitted.
std::vector<SensorNoiseParameters> filter_noise_parameters(const AllanChannels& channels);

enum class FilterFormat { kKalibr, kMatlab, kGnssInsSim, kJson };
// "kalibr", "matlab", "gnss-ins-sim", "json"; throws Error listing them.
FilterFormat parse_filter_format(std::string_view text);

// The file's text. The gyro channels, then the accelerometer channels, in the order given, are the
// x, y, z axes. Kalibr takes one value per sensor (the largest of its axes, the conservative
// choice) and needs both sensors; MATLAB's gyroparams/accelparams one axis or three; gnss-ins-sim
// three of each, and has no random-walk term (the file says K is left out). Channels a target
// cannot load are an Error, before any text. MATLAB and gnss-ins-sim get the record's sample rate
// and the discrete values in comments. `command` is quoted in the file's header comment.
std::string format_filter_parameters(const std::vector<SensorNoiseParameters>& sensors, FilterFormat format,
                                     const std::string& command);

nlohmann::json filter_parameters_json(const std::vector<SensorNoiseParameters>& sensors);

}  // namespace inertest

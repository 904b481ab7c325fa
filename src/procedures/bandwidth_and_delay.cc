#include "inertest/procedures/bandwidth_and_delay.h"

#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/numerics/compensated_sum.h"
#include "inertest/numerics/least_squares.h"

namespace inertest {
namespace {

using constants::kPi;
constexpr double kTwoPi = 2.0 * kPi;
constexpr std::size_t kFewestFrequencies = 3;  // two parameters of eq. (37) plus one degree of freedom

double wrap_to_pi(double angle) {
  double wrapped = std::remainder(angle, kTwoPi);  // in [-π, π]
  if (wrapped <= -kPi) wrapped += kTwoPi;
  return wrapped;
}

void check_points(std::span<const FrequencyResponsePoint> points, const BandwidthOptions& options) {
  if (points.size() < options.minimum_frequencies) {
    throw Error(fmt::format("bandwidth: {} frequencies; GJB 2426A 5.13.3 a) asks for at least {}", points.size(),
                            options.minimum_frequencies));
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    if (!std::isfinite(p.frequency_hz) || p.frequency_hz <= 0.0) {
      throw Error(fmt::format("bandwidth: point {}: frequency {} Hz is not positive", i + 1, p.frequency_hz));
    }
    if (i > 0 && !(p.frequency_hz > points[i - 1].frequency_hz)) {
      throw Error(fmt::format("bandwidth: point {}: frequency {} Hz is not above the one before ({} Hz); the "
                              "frequencies must increase",
                              i + 1, p.frequency_hz, points[i - 1].frequency_hz));
    }
    if (!std::isfinite(p.gain) || p.gain <= 0.0) {
      throw Error(fmt::format("bandwidth: point {}: gain {} is not positive", i + 1, p.gain));
    }
    if (!std::isfinite(p.phase_rad)) throw Error(fmt::format("bandwidth: point {}: phase is not finite", i + 1));
  }
}

// Phases are known modulo a turn (a sine fit's; an analyser's ±180°, 0 to −360° or 0 to 360°; or
// unwrapped already). The first is taken into (−180°, 180°], each next so that from its neighbour
// the lag grows by less than 300° or shrinks by less than 60° (noise, where the phase is flat at low
// frequencies): a gyro's lag grows with frequency. Taking each step the short way made a step of
// 230° one of −130° (Td 0.86 ms for 1.5); keeping phases as given read a first phase of 354° (0 to
// 360°, unwrapped) as a negative polarity.
std::vector<double> unwrapped_phases(std::span<const FrequencyResponsePoint> points) {
  constexpr double kLargestLead = kPi / 3.0;
  std::vector<double> phases;
  for (const auto& p : points) {
    if (phases.empty()) {
      phases.push_back(wrap_to_pi(p.phase_rad));
      continue;
    }
    double short_of_lead = std::fmod(kLargestLead - (p.phase_rad - phases.back()), 2.0 * kPi);
    if (short_of_lead < 0.0) short_of_lead += 2.0 * kPi;
    phases.push_back(phases.back() + kLargestLead - short_of_lead);  // a step in (60° − 360°, 60°]
  }
  return phases;
}

// The largest growth of the lag between neighbouring frequencies, in rad.
double largest_lag_step(const std::vector<double>& phases) {
  double largest = 0.0;
  for (std::size_t i = 1; i < phases.size(); ++i) largest = std::max(largest, phases[i - 1] - phases[i]);
  return largest;
}

// Polarity (reference README §3, "Polarity"): a gyro of negative scale factor (output falling as the
// rate rises) has every phase of eq. (43) offset by π, which eqs. (44)-(46) would read as a delay.
// The model of eq. (42) puts the phase at the lowest frequency, well below the bandwidth, in
// (−π/2, 0] less ωL·Td, so a phase there beyond ±π/2 is the polarity, not a lag: π is taken from
// every phase (keeping them unwrapped). Returns the polarity, +1 or −1 (the sign of K).
int remove_polarity(std::vector<double>& phases) {
  if (std::abs(phases.front()) <= kPi / 2.0) return 1;
  const double offset = phases.front() > 0.0 ? kPi : -kPi;
  for (double& p : phases) p -= offset;
  return -1;
}

}  // namespace

void BandwidthOptions::validate() const {
  if (minimum_frequencies < kFewestFrequencies) {
    throw Error(fmt::format("bandwidth: the minimum number of frequencies cannot be below {}", kFewestFrequencies));
  }
  if (Unit::parse(angle_unit).dimension() != Unit::parse("rad").dimension()) {
    throw Error("bandwidth: angle unit '" + angle_unit + "' is not an angle");
  }
  Unit::parse(output_unit);
}

BandwidthResult bandwidth_and_delay(std::span<const FrequencyResponsePoint> points, const BandwidthOptions& options) {
  options.validate();
  check_points(points, options);
  const std::size_t n = points.size();
  std::vector<double> omega(n);
  for (std::size_t i = 0; i < n; ++i) omega[i] = kTwoPi * points[i].frequency_hz;  // ωi in rad/s

  // Eqs. (37)-(40): Y = X·B with Y = Gi², X = [1, −Gi²ωi²], B = [K², T²].
  Matrix design(n, 2);
  std::vector<double> gain_squared(n);
  for (std::size_t i = 0; i < n; ++i) {
    gain_squared[i] = points[i].gain * points[i].gain;
    design(i, 0) = 1.0;
    design(i, 1) = -gain_squared[i] * omega[i] * omega[i];
  }
  LeastSquaresOptions fit_options;
  fit_options.parameter_names = {"K^2", "T^2"};
  // The noise of Gi² differs between frequencies (a fixed output noise over an amplitude that falls
  // with frequency, on both sides of eq. 37): one residual variance for all understated u(Bw) 1.6
  // times (48 % of 2000 trials within 1 sigma, 65 % with HC3; the test BandwidthAndDelay.
  // UncertaintiesCoverTheTruthWhenTheNoiseGrowsWithFrequency).
  fit_options.heteroscedastic = true;
  const LeastSquaresResult fit = solve_least_squares(design, gain_squared, fit_options);
  const double k_squared = fit.parameters[0];
  const double t_squared = fit.parameters[1];
  if (!(t_squared > 0.0)) {
    throw Error(fmt::format("bandwidth: the fit of eq. (37) gives T^2 = {:.6g} s^2 <= 0: the gains do not fall with "
                            "frequency like a first-order lag, so no bandwidth can be determined (test up to twice "
                            "the bandwidth, GJB 2426A 5.13.3 a)",
                            t_squared));
  }
  if (!(k_squared > 0.0)) {
    throw Error(fmt::format("bandwidth: the fit of eq. (37) gives K^2 = {:.6g} <= 0; no bandwidth can be determined",
                            k_squared));
  }
  const double t = std::sqrt(t_squared);                  // eq. (38)
  const double bandwidth = 1.0 / (kTwoPi * t);            // eq. (41)
  const double k = std::sqrt(k_squared);
  const double variance_k2 = fit.covariance(0, 0);
  const double variance_t2 = fit.covariance(1, 1);
  const double sigma_t = std::sqrt(std::max(0.0, variance_t2)) / (2.0 * t);
  // dBw/d(T²) = −Bw/(2T²).
  const double sigma_bandwidth = bandwidth * std::sqrt(std::max(0.0, variance_t2)) / (2.0 * t_squared);
  const double sigma_k = std::sqrt(std::max(0.0, variance_k2)) / (2.0 * k);

  // Eqs. (44)-(46): Td = Σ ωi·yi / Σ ωi², yi = −Pi − atan(ωi·T), on the phases with the polarity's π removed.
  std::vector<double> phase = unwrapped_phases(points);
  const int polarity = remove_polarity(phase);
  CompensatedSum omega_y;
  CompensatedSum omega_omega;
  CompensatedSum d_omega_y_dt;  // Σ ωi · dyi/dT, for the share of T's uncertainty in Td
  std::vector<double> y(n);
  for (std::size_t i = 0; i < n; ++i) {
    y[i] = -phase[i] - std::atan(omega[i] * t);
    omega_y.add(omega[i] * y[i]);
    omega_omega.add(omega[i] * omega[i]);
    d_omega_y_dt.add(-omega[i] * omega[i] / (1.0 + omega[i] * omega[i] * t * t));
  }
  const double delay = omega_y.value() / omega_omega.value();
  CompensatedSum phase_rss;
  for (std::size_t i = 0; i < n; ++i) phase_rss.add((y[i] - omega[i] * delay) * (y[i] - omega[i] * delay));
  // HC3 variance of the one-parameter fit, each phase by its own residual (a phase's noise grows as
  // 1/Gi, largest at the high frequencies that weigh most in Td: one residual variance for all held
  // the truth in 45 % of trials within 1 sigma, HC3 in 69 %), plus T's uncertainty carried through
  // atan(ωi·T) (the two taken as independent). Leverage h_i = ωi² / Σ ωj².
  CompensatedSum delay_meat;
  for (std::size_t i = 0; i < n; ++i) {
    const double free = 1.0 - omega[i] * omega[i] / omega_omega.value();
    if (free < 1e-8) continue;  // the only frequency: its residual is 0 by construction
    const double e = (y[i] - omega[i] * delay) / free;
    delay_meat.add(omega[i] * omega[i] * e * e);
  }
  const double sigma_delay_fit = std::sqrt(delay_meat.value()) / omega_omega.value();
  const double sigma_delay_t = std::abs(d_omega_y_dt.value() / omega_omega.value()) * sigma_t;

  BandwidthResult result;
  result.bandwidth = {bandwidth, "Hz", sigma_bandwidth};
  result.delay = {delay, "s", std::hypot(sigma_delay_fit, sigma_delay_t)};
  result.dc_gain = {k, "1", sigma_k};
  result.time_constant = {t, "s", sigma_t};
  result.gain_fit_residual_rms = {fit.residual_rms, "1", std::nullopt};
  result.phase_fit_residual_rms = {std::sqrt(phase_rss.value() / static_cast<double>(n)) / constants::kDegree, "deg",
                                   std::nullopt};
  result.angle_unit = options.angle_unit;
  result.polarity = polarity;
  for (std::size_t i = 0; i < n; ++i) {
    const double fitted_gain = k / std::sqrt(1.0 + omega[i] * omega[i] * t_squared);
    const double fitted_phase = -std::atan(omega[i] * t) - omega[i] * delay;
    result.bode.push_back({points[i].frequency_hz, points[i].gain, fitted_gain, phase[i] / constants::kDegree,
                           fitted_phase / constants::kDegree});
  }
  if (n < 10) {
    result.warnings.push_back(fmt::format("{} frequencies; GJB 2426A 5.13.3 a) asks for at least 10", n));
  }
  // A delay below zero by more than twice its uncertainty, and by more than a tenth of a degree of
  // phase at the highest frequency, has the output lead the input: no gyro does. The phases are then
  // not eq. (43)'s (the output's phase against the input rate, a lag negative): a lag entered as a
  // positive number, or a phase against the angle (90 deg off).
  if (delay < -2.0 * *result.delay.uncertainty && -delay * omega.back() > 0.1 * constants::kDegree) {
    result.warnings.push_back(fmt::format(
        "the output delay Td = {:.6g} s is negative (the output would lead the input): are the phases the "
        "output's against the input rate, a lag negative, in degrees (GJB 2426A eq. (43))?",
        delay));
  }
  // Eq. (42)'s lag and delay leave a few degrees at most on a gyro's phases; tens of degrees are a
  // response the model does not describe (a resonance, a mixed-up column), and Td is no figure of it.
  constexpr double kPhaseResidualWarningDeg = 10.0;
  if (result.phase_fit_residual_rms.value > kPhaseResidualWarningDeg) {
    result.warnings.push_back(fmt::format("the phases depart from eq. (42)'s lag and delay by {:.3g} deg rms (over {} "
                                          "deg): the output delay is no figure of this response",
                                          result.phase_fit_residual_rms.value, kPhaseResidualWarningDeg));
  }
  // A lag growing by more than 180 deg between neighbours is taken as a lag (see unwrapped_phases),
  // not as the lead the short way round would make it: said, as it rests on that.
  if (largest_lag_step(phase) > kPi) {
    result.warnings.push_back(fmt::format("the lag grows by up to {:.0f} deg between neighbouring frequencies, taken "
                                          "as a lag (not the lead of {:.0f} deg the other way round); test more "
                                          "frequencies to close the gap",
                                          largest_lag_step(phase) / constants::kDegree,
                                          360.0 - largest_lag_step(phase) / constants::kDegree));
  }
  if (points.back().frequency_hz < 2.0 * bandwidth) {
    result.warnings.push_back(fmt::format("the highest frequency ({} Hz) is below twice the bandwidth ({:.6g} Hz); "
                                          "GJB 2426A 5.13.3 a) tests up to twice the bandwidth",
                                          points.back().frequency_hz, 2.0 * bandwidth));
  }
  return result;
}

std::vector<VibrationFit> fit_vibration_records(std::span<const AngularVibrationRecord> records,
                                                const BandwidthOptions& options) {
  options.validate();
  const double angle_to_rad = convert(1.0, options.angle_unit, "rad");
  std::vector<VibrationFit> fits;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const auto& record = records[i];
    const std::string name = record.source.empty() ? fmt::format("record {}", i + 1) : record.source;
    if (!std::isfinite(record.frequency_hz) || record.frequency_hz <= 0.0) {
      throw Error(fmt::format("bandwidth: {}: frequency {} Hz is not positive", name, record.frequency_hz));
    }
    if (record.output.size() != record.time_s.size() || record.angle.size() != record.time_s.size()) {
      throw Error(fmt::format("bandwidth: {}: time, output and angle differ in length", name));
    }
    const double omega = kTwoPi * record.frequency_hz;
    VibrationFit fit;
    fit.frequency_hz = record.frequency_hz;
    try {
      fit.output = fit_sine(record.time_s, record.output, omega);  // eq. (34)
      fit.angle = fit_sine(record.time_s, record.angle, omega);    // eq. (32)
    } catch (const Error& e) {
      throw Error(fmt::format("bandwidth: {}: {}", name, e.message()));
    }
    if (!(fit.angle.amplitude * angle_to_rad > 0.0) || !(fit.output.amplitude > 0.0)) {
      throw Error(fmt::format("bandwidth: {}: no vibration at {} Hz in the {}", name, record.frequency_hz,
                              fit.angle.amplitude > 0.0 ? "output" : "angle"));
    }
    fit.rate_amplitude = fit.angle.amplitude * omega;  // eq. (33)
    fits.push_back(fit);
  }
  return fits;
}

BandwidthResult bandwidth_and_delay(std::span<const AngularVibrationRecord> records, const BandwidthOptions& options) {
  const std::vector<VibrationFit> fits = fit_vibration_records(records, options);
  if (fits.empty()) throw Error("bandwidth: no records");
  std::vector<FrequencyResponsePoint> points;
  const double reference = fits.front().output.amplitude / fits.front().rate_amplitude;  // FL / RL
  for (const auto& fit : fits) {
    // Eq. (35) with the rate amplitude divided out; eq. (43): the rate leads the angle by π/2
    // (θ = A·sin(ωt + Φθ) gives θ' = Aω·sin(ωt + Φθ + π/2)), so the output's phase against the
    // rate is Φ_F − Φθ − π/2, zero for an ideal gyro and negative for a lag.
    const double gain = (fit.output.amplitude / fit.rate_amplitude) / reference;
    points.push_back({fit.frequency_hz, gain, wrap_to_pi(fit.output.phase - fit.angle.phase - kPi / 2.0)});
  }
  BandwidthResult result = bandwidth_and_delay(points, options);
  result.vibration_fits = fits;
  result.output_unit = options.output_unit;
  return result;
}

}  // namespace inertest

#include "inertest/allan/noise_identification.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "inertest/core/error.h"

namespace inertest {
namespace {

NoiseType clamped_noise_type(long alpha) {
  switch (std::clamp(alpha, -2L, 2L)) {
    case 2: return NoiseType::kWhitePhase;
    case 1: return NoiseType::kFlickerPhase;
    case 0: return NoiseType::kWhiteFrequency;
    case -1: return NoiseType::kFlickerFrequency;
    default: return NoiseType::kRandomWalkFrequency;
  }
}

// R(n) = MVAR/AVAR expected at factor m (NIST TN 1337 Table A-6): white PM 1/m; flicker PM
// 3.37 / (1.04 + 3 ln(omega_h tau)) with the measurement bandwidth f_h = 1/(2 tau0), so that
// omega_h tau = pi m; white FM 1/2.
double rn_white_phase(double m) { return 1.0 / m; }
double rn_flicker_phase(double m) { return 3.37 / (1.04 + 3.0 * std::log(std::numbers::pi * m)); }
constexpr double kRnWhiteFrequency = 0.5;

// The phase noise that R(n) points to, boundaries at the geometric means of the expectations.
NoiseType phase_noise_from_rn(double rn, double m) {
  if (rn < std::sqrt(rn_white_phase(m) * rn_flicker_phase(m))) return NoiseType::kWhitePhase;
  if (rn < std::sqrt(rn_flicker_phase(m) * kRnWhiteFrequency)) return NoiseType::kFlickerPhase;
  return NoiseType::kWhiteFrequency;
}

// The N of B1's expectation: the estimator's number of terms, counted from the averages for ADEV
// and HDEV (floor(N/m) - 1 and - 2, as the engine counts them) so that they need not be computed.
std::size_t b1_term_count(Estimator estimator, const AllanSums& sums) {
  const std::size_t averages = sums.averages.series(0).count();
  switch (estimator) {
    case Estimator::kAdev: return averages > 1 ? averages - 1 : 0;
    case Estimator::kHdev: return averages > 2 ? averages - 2 : 0;
    default: return sums.terms(estimator);
  }
}

}  // namespace

std::string_view noise_identification_method_name(NoiseIdentificationMethod method) {
  switch (method) {
    case NoiseIdentificationMethod::kLag1Autocorrelation: return "lag1_autocorrelation";
    case NoiseIdentificationMethod::kB1Ratio: return "b1_ratio";
    case NoiseIdentificationMethod::kB1RatioAndRn: return "b1_ratio_and_rn";
    case NoiseIdentificationMethod::kShorterTau: return "shorter_tau";
    case NoiseIdentificationMethod::kNotIdentified: return "not_identified";
  }
  return "";
}

std::optional<double> lag1_alpha(const AveragedFrequencySeries& averages, std::size_t max_differences) {
  if (max_differences >= AveragedFrequencySeries::kOrders) {
    throw Error("lag-1 noise identification: at most " + std::to_string(AveragedFrequencySeries::kOrders - 1) +
                " differences of the averaged frequency");
  }
  for (std::size_t d = 0;; ++d) {
    const double r1 = averages.series(d).autocorrelation();
    if (!std::isfinite(r1) || r1 <= -1.0) return std::nullopt;
    const double delta = r1 / (1.0 + r1);  // Riley & Greenhall (2004): delta of (2 sin(pi f))^(-2 delta)
    if (delta < 0.25 || d == max_differences) return -2.0 * (delta + static_cast<double>(d));
  }
}

double b1_expected(double n, int mu) {
  switch (mu) {
    case 2: return n * (n + 1.0) / 6.0;
    case 1: return n / 2.0;
    case 0: return n * std::log(n) / (2.0 * (n - 1.0) * std::log(2.0));
    case -1: return 1.0;
    case -2: return (n * n - 1.0) / (1.5 * n * (n - 1.0));
    default: break;
  }
  throw Error("B1 ratio: the Allan-variance slope mu = " + std::to_string(mu) + " is outside -2 .. 2");
}

int b1_mu(double b1, double n) {
  for (int mu = 2; mu > -2; --mu) {
    const double upper = b1_expected(n, mu);
    const double lower = b1_expected(n, mu - 1);
    const double boundary = mu == 2 ? (upper + lower) / 2.0 : std::sqrt(upper * lower);
    if (b1 > boundary) return mu;
  }
  return -2;
}

NoiseIdentification identify_power_law_noise(Estimator estimator, const AllanSums& sums) {
  const Lag1Sums& averages = sums.averages.series(0);
  if (averages.count() >= kLag1MinimumAverages) {
    const bool hadamard = estimator == Estimator::kHdev || estimator == Estimator::kOhdev;
    const std::optional<double> p = lag1_alpha(sums.averages, hadamard ? 2 : 1);
    if (!p) return {};
    return {clamped_noise_type(std::lround(*p)), NoiseIdentificationMethod::kLag1Autocorrelation};
  }
  // Howe et al. (2000): B1 = the N-sample variance of the non-overlapping averages over the
  // (non-overlapping) Allan variance of the same averages, 1/2 the mean square of their first
  // differences (identify_power_law_noise in the header).
  const double allan_variance = 0.5 * sums.averages.series(1).mean_square();
  const double b1 = averages.sample_variance() / allan_variance;
  const auto terms = static_cast<double>(b1_term_count(estimator, sums));
  if (!std::isfinite(b1) || !(terms >= 2.0)) return {};
  const int mu = b1_mu(b1, terms);
  if (mu > -2) {
    // Howe et al. (2000) Table 4: alpha = -mu - 1 for the FM noises.
    return {clamped_noise_type(-mu - 1), NoiseIdentificationMethod::kB1Ratio};
  }
  if (estimator != Estimator::kMdev) return {NoiseType::kWhiteFrequency, NoiseIdentificationMethod::kB1Ratio};
  const double rn = sums.variance(Estimator::kMdev) / allan_variance;
  return {phase_noise_from_rn(rn, static_cast<double>(sums.averaging_factor)), NoiseIdentificationMethod::kB1RatioAndRn};
}

std::vector<NoiseIdentification> identify_along_taus(Estimator estimator, std::span<const AllanSums> sums) {
  std::vector<NoiseIdentification> noise;
  noise.reserve(sums.size());
  for (const AllanSums& s : sums) noise.push_back(identify_power_law_noise(estimator, s));
  if (noise.size() >= 2 && sums.back().averages.series(0).count() < kLag1MinimumAverages) {
    noise.back() = {noise[noise.size() - 2].type, NoiseIdentificationMethod::kShorterTau};
  }
  return noise;
}

}  // namespace inertest

#include "inertest/allan/confidence.h"

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>

#include "inertest/core/error.h"

namespace inertest {

std::string_view noise_type_name(NoiseType type) {
  switch (type) {
    case NoiseType::kWhitePhase: return "white_pm";
    case NoiseType::kFlickerPhase: return "flicker_pm";
    case NoiseType::kWhiteFrequency: return "white_fm";
    case NoiseType::kFlickerFrequency: return "flicker_fm";
    case NoiseType::kRandomWalkFrequency: return "random_walk_fm";
  }
  return "";
}

double edf_overlapping_allan(double n, double m, NoiseType type) {
  switch (type) {
    case NoiseType::kWhitePhase: return (n + 1.0) * (n - 2.0 * m) / (2.0 * (n - m));
    case NoiseType::kFlickerPhase:
      return std::exp(std::sqrt(std::log((n - 1.0) / (2.0 * m)) * std::log((2.0 * m + 1.0) * (n - 1.0) / 4.0)));
    case NoiseType::kWhiteFrequency:
      return (3.0 * (n - 1.0) / (2.0 * m) - 2.0 * (n - 2.0) / n) * (4.0 * m * m / (4.0 * m * m + 5.0));
    case NoiseType::kFlickerFrequency:
      return m == 1.0 ? 2.0 * (n - 2.0) / (2.3 * n - 4.9) : 5.0 * n * n / (4.0 * m * (n + 3.0 * m));
    case NoiseType::kRandomWalkFrequency:
      return (n - 2.0) / (m * (n - 3.0) * (n - 3.0)) * ((n - 1.0) * (n - 1.0) - 3.0 * m * (n - 1.0) + 4.0 * m * m);
  }
  return n - 1.0;
}

double edf_total(double sample_count, double m, NoiseType type) {
  switch (type) {
    case NoiseType::kWhiteFrequency: return 1.50 * sample_count / m;
    case NoiseType::kFlickerFrequency: return 1.17 * sample_count / m - 0.22;
    case NoiseType::kRandomWalkFrequency: return 0.93 * sample_count / m - 0.36;
    case NoiseType::kWhitePhase:
    case NoiseType::kFlickerPhase: break;
  }
  return edf_overlapping_allan(sample_count + 1.0, m, type);
}

double equivalent_degrees_of_freedom(Estimator estimator, std::size_t sample_count, std::size_t m,
                                     std::size_t term_count, NoiseType type) {
  const double n = static_cast<double>(sample_count);
  const double factor = static_cast<double>(m);
  const double decimated = static_cast<double>(sample_count / m) + 1.0;
  double edf = 0.0;
  switch (estimator) {
    case Estimator::kAdev:
    case Estimator::kHdev: edf = edf_overlapping_allan(decimated, 1.0, type); break;
    case Estimator::kOadev:
    case Estimator::kOhdev:
    case Estimator::kMdev: edf = edf_overlapping_allan(n + 1.0, factor, type); break;
    case Estimator::kTotdev: edf = edf_total(n, factor, type); break;
  }
  // The simple formulae leave their range at the largest factors (few terms): keep 1 <= edf <= terms.
  if (!(edf >= 1.0)) edf = 1.0;
  return std::max(1.0, std::min(edf, static_cast<double>(term_count)));
}

DeviationInterval chi_squared_interval(double deviation, double edf, double confidence) {
  if (!(edf > 0.0)) throw Error("equivalent degrees of freedom must be positive");
  if (!(confidence > 0.0 && confidence < 1.0)) throw Error("confidence level must lie between 0 and 1");
  const boost::math::chi_squared_distribution<double> chi_squared(edf);
  const double tail = (1.0 - confidence) / 2.0;
  const double low_quantile = boost::math::quantile(chi_squared, tail);
  const double high_quantile = boost::math::quantile(chi_squared, 1.0 - tail);
  return {deviation * std::sqrt(edf / high_quantile), deviation * std::sqrt(edf / low_quantile)};
}

}  // namespace inertest

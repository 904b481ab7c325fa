#include "inertest/allan/confidence.h"

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <limits>

#include "inertest/core/error.h"

namespace inertest {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Greenhall & Riley (2003) eq. (7): the generalised autocovariance of the phase for S_y ~ f^alpha,
// up to a factor that is constant for one alpha (and cancels in the edf).
double greenhall_sw(double t, int alpha) {
  const double a = std::abs(t);
  switch (alpha) {
    case 2: return -a;
    case 1: return t == 0.0 ? 0.0 : t * t * std::log(a);
    case 0: return a * a * a;
    case -1: return t == 0.0 ? 0.0 : -std::pow(t, 4) * std::log(a);
    case -2: return -std::pow(a, 5);
    case -3: return t == 0.0 ? 0.0 : std::pow(t, 6) * std::log(a);
    case -4: return std::pow(a, 7);
    default: break;
  }
  throw Error("Greenhall edf: noise exponent alpha = " + std::to_string(alpha) + " is outside +2..-4");
}

// Eq. (8): the phase filtered by the averaging filter of factor F (F = infinity: the limit, the
// second derivative, which is sw for alpha + 2 up to a constant).
double greenhall_sx(double t, double f, int alpha) {
  if (f == kInfinity) return greenhall_sw(t, alpha + 2);
  return f * f * (2.0 * greenhall_sw(t, alpha) - greenhall_sw(t - 1.0 / f, alpha) - greenhall_sw(t + 1.0 / f, alpha));
}

// Eq. (9): the d-th difference, sum_k (-1)^k C(2d, d+k) sx(t + k).
double greenhall_sz(double t, double f, int alpha, int d) {
  static constexpr double kBinomial[4][7] = {
      {1, 0, 0, 0, 0, 0, 0}, {1, 2, 1, 0, 0, 0, 0}, {1, 4, 6, 4, 1, 0, 0}, {1, 6, 15, 20, 15, 6, 1}};
  double sum = 0.0;
  for (int k = -d; k <= d; ++k) {
    const double sign = (k % 2 == 0) ? 1.0 : -1.0;
    sum += sign * kBinomial[d][d + k] * greenhall_sx(t + k, f, alpha);
  }
  return sum;
}

// Eq. (10), the basic sum: sz(0)^2 + 2 sum_{j=1}^{J-1} (1 - j/M) sz(j/S)^2 + (1 - J/M) sz(J/S)^2.
// For white PM (alpha = 2) unmodified (F = m), sz(j/S) vanishes unless j/S is a whole number (the
// filtered phase is a tent of half-width 1/m), so only those j are summed: exact for any J.
double greenhall_basic_sum(double j_count, double big_m, double s, double f, int alpha, int d) {
  const auto term = [&](double j) {
    const double z = greenhall_sz(j / s, f, alpha, d);
    return z * z;
  };
  double sum = term(0.0) + (1.0 - j_count / big_m) * term(j_count);
  const bool tent = alpha == 2 && f != kInfinity && f > 1.0;
  const double step = tent ? s : 1.0;
  for (double j = step; j < j_count; j += step) sum += 2.0 * (1.0 - j / big_m) * term(j);
  return sum;
}

// Greenhall & Riley (2003) Table 1 (modified variances) and Table 2 (unmodified), (a0, a1) of
// 1/edf = (1/r)(a0 - a1/r) for large r; rows alpha = +2 .. -2, columns d = 1..3 (0: not defined).
struct TableEntry {
  double a0;
  double a1;
};
constexpr TableEntry kTable1[5][3] = {{{2.0 / 3.0, 1.0 / 3.0}, {7.0 / 9.0, 1.0 / 2.0}, {22.0 / 25.0, 2.0 / 3.0}},
                                      {{0.840, 0.345}, {0.997, 0.616}, {1.141, 0.843}},
                                      {{1.079, 0.368}, {1.033, 0.607}, {1.184, 0.848}},
                                      {{0.0, 0.0}, {1.048, 0.534}, {1.180, 0.816}},
                                      {{0.0, 0.0}, {1.302, 0.535}, {1.175, 0.777}}};
constexpr TableEntry kTable2[5][3] = {{{3.0 / 2.0, 1.0 / 2.0}, {35.0 / 18.0, 1.0}, {231.0 / 100.0, 3.0 / 2.0}},
                                      {{78.6, 25.2}, {790.0, 410.0}, {9950.0, 6520.0}},
                                      {{2.0 / 3.0, 1.0 / 6.0}, {2.0 / 3.0, 1.0 / 3.0}, {7.0 / 9.0, 1.0 / 2.0}},
                                      {{0.0, 0.0}, {0.852, 0.375}, {0.997, 0.617}},
                                      {{0.0, 0.0}, {1.079, 0.368}, {1.033, 0.607}}};
// Table 3 (unmodified, flicker PM): sz(0)^2 ~ (b0 + b1 ln m)^2 for large m.
constexpr TableEntry kTable3[3] = {{6.0, 4.0}, {15.23, 12.0}, {47.8, 40.0}};

}  // namespace

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

double edf_total(double phase_count, double m, NoiseType type) {
  switch (type) {
    case NoiseType::kWhiteFrequency: return 1.50 * phase_count / m;
    case NoiseType::kFlickerFrequency: return 1.17 * phase_count / m - 0.22;
    case NoiseType::kRandomWalkFrequency: return 0.93 * phase_count / m - 0.36;
    case NoiseType::kWhitePhase:
    case NoiseType::kFlickerPhase: break;
  }
  return edf_overlapping_allan(phase_count, m, type);
}

double edf_greenhall(NoiseType type, int d, double m, double phase_count, bool overlapping, bool modified) {
  const int alpha = static_cast<int>(type);
  if (d < 1 || d > 3 || alpha + 2 * d <= 1) {
    throw Error("Greenhall edf: d = " + std::to_string(d) + " with alpha = " + std::to_string(alpha) +
                " is outside the algorithm (1 <= d <= 3, alpha + 2d > 1)");
  }
  if (!(m >= 1.0)) throw Error("Greenhall edf: the averaging factor must be at least 1");
  const double f = modified ? 1.0 : m;   // filter factor F
  const double s = overlapping ? m : 1.0;  // stride factor S
  const double length = m / f + m * d;   // L, phase points spanned by one term
  const double big_m = 1.0 + std::floor(s * (phase_count - length) / m);  // M, the number of terms
  if (!(big_m >= 1.0)) throw Error("Greenhall edf: the record holds no term at this averaging factor");
  const double j_count = std::min(big_m, (d + 1) * s);  // J
  constexpr double kJmax = 100.0;
  const double r = big_m / s;
  const TableEntry* row1 = kTable1[2 - alpha];
  const TableEntry* row2 = kTable2[2 - alpha];
  double inverse = 0.0;
  const auto z0_squared = [&](double filter) {
    const double z = greenhall_sz(0.0, filter, alpha, d);
    return z * z;
  };
  if (modified) {
    // Case 1: modified variances, every alpha.
    if (j_count <= kJmax) {
      inverse = greenhall_basic_sum(j_count, big_m, s, 1.0, alpha, d) / (z0_squared(1.0) * big_m);
    } else if (r > d + 1) {
      inverse = (row1[d - 1].a0 - row1[d - 1].a1 / r) / r;
    } else {
      inverse = greenhall_basic_sum(kJmax, kJmax, kJmax / r, 1.0, alpha, d) / (z0_squared(1.0) * kJmax);
    }
  } else if (alpha <= 0) {
    // Case 2: unmodified variances, alpha <= 0.
    if (j_count <= kJmax) {
      const double filter = m * (d + 1) <= kJmax ? m : kInfinity;
      inverse = greenhall_basic_sum(j_count, big_m, s, filter, alpha, d) / (z0_squared(filter) * big_m);
    } else if (r > d + 1) {
      inverse = (row2[d - 1].a0 - row2[d - 1].a1 / r) / r;
    } else {
      inverse = greenhall_basic_sum(kJmax, kJmax, kJmax / r, kInfinity, alpha, d) / (z0_squared(kInfinity) * kJmax);
    }
  } else if (alpha == 1) {
    // Case 3: unmodified variances, flicker PM.
    const TableEntry b = kTable3[d - 1];
    const double z0 = b.a0 + b.a1 * std::log(m);
    if (j_count <= kJmax) {
      inverse = greenhall_basic_sum(j_count, big_m, s, m, alpha, d) / (z0_squared(m) * big_m);
    } else if (r > d + 1) {
      inverse = (row2[d - 1].a0 - row2[d - 1].a1 / r) / (z0 * z0 * r);
    } else {
      inverse = greenhall_basic_sum(kJmax, kJmax, kJmax / r, kJmax / r, alpha, d) / (z0 * z0 * kJmax);
    }
  } else {
    // Case 4: unmodified variances, white PM: the basic sum is exact here (see greenhall_basic_sum)
    // and equals the paper's (1/M)(a0 - a1/r) with a0 = C(4d,2d)/C(2d,d)^2, a1 = d/2 when r > d.
    inverse = greenhall_basic_sum(j_count, big_m, s, m, alpha, d) / (z0_squared(m) * big_m);
  }
  return 1.0 / inverse;
}

double equivalent_degrees_of_freedom(Estimator estimator, std::size_t sample_count, std::size_t m, NoiseType type) {
  const double phase_count = static_cast<double>(sample_count) + 1.0;
  const double factor = static_cast<double>(m);
  double edf = 0.0;
  switch (estimator) {
    case Estimator::kAdev: edf = edf_greenhall(type, 2, factor, phase_count, false, false); break;
    case Estimator::kOadev: edf = edf_greenhall(type, 2, factor, phase_count, true, false); break;
    case Estimator::kMdev: edf = edf_greenhall(type, 2, factor, phase_count, true, true); break;
    case Estimator::kHdev: edf = edf_greenhall(type, 3, factor, phase_count, false, false); break;
    case Estimator::kOhdev: edf = edf_greenhall(type, 3, factor, phase_count, true, false); break;
    case Estimator::kTotdev: edf = edf_total(phase_count, factor, type); break;
  }
  // The simple formulae of Tables 5 and 7 leave their range at the largest factors.
  return edf >= 1.0 ? edf : 1.0;
}

std::string_view edf_method(Estimator estimator) {
  switch (estimator) {
    case Estimator::kAdev:
    case Estimator::kOadev:
    case Estimator::kMdev:
    case Estimator::kHdev:
    case Estimator::kOhdev: return "Greenhall & Riley 2003 combined algorithm (NIST SP 1065 5.3)";
    case Estimator::kTotdev: return "NIST SP 1065 Table 7 (Table 5 for PM noise)";
  }
  return "";
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

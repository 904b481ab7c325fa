#include "inertest/allan/noise_terms.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>
#include <mutex>
#include <tuple>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "allan/noise_figures.h"
#include "numerics/non_negative_least_squares.h"

namespace inertest {
namespace {

using detail::coefficient_covariance;
using detail::figure_of;
using detail::kSignificance;
using detail::noise_figure_json;
using detail::FigureUnits;
using detail::solve_scaled_non_negative;
using detail::units_for;

constexpr int kTerms = 5;  // p = -2..2
// The indices p + 2 of the long-tau terms A_1 (K) and A_2 (R).
constexpr std::size_t kRateRandomWalk = 3;
constexpr std::size_t kRateRamp = 4;

void check_points(std::span<const double> tau_s, std::span<const double> values, std::span<const double> edf) {
  if (tau_s.size() != values.size() || tau_s.size() != edf.size()) throw Error("tau, values and edf differ in length");
  if (tau_s.size() < 2) throw Error("noise identification needs at least 2 averaging times");
  for (std::size_t i = 0; i < tau_s.size(); ++i) {
    if (!(tau_s[i] > 0.0) || !(values[i] > 0.0) || !(edf[i] > 0.0)) {
      throw Error("noise identification needs positive tau, deviations and edf (point " + std::to_string(i + 1) + ")");
    }
    // The model's terms go as tau^-2 .. tau^2, and the fit runs in units of the shortest tau: an
    // averaging time whose square a double cannot hold (a sample rate of 1e300 Hz) gave inf there.
    if (!std::isnormal(tau_s[i] * tau_s[i]) || !std::isnormal(1.0 / (tau_s[i] * tau_s[i]))) {
      throw Error(fmt::format("noise identification: the averaging time {:g} s (point {}) is beyond the range whose "
                              "square a double holds (about 1e-154 to 1e154 s): is the sample rate in Hz?",
                              tau_s[i], i + 1));
    }
    // The fit range drops the shortest taus first and the slopes pair neighbours: in another order
    // the same curve gave other figures.
    if (i > 0 && !(tau_s[i] > tau_s[i - 1])) {
      throw Error(fmt::format("noise identification needs increasing taus (point {}: {:g} s after {:g} s)", i + 1,
                              tau_s[i], tau_s[i - 1]));
    }
  }
}

// Whether two of the taus lie less than an octave apart (within a relative 1e-9).
bool closer_than_an_octave(std::span<const double> tau_s) {
  std::vector<double> sorted(tau_s.begin(), tau_s.end());
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    if (sorted[i] < 2.0 * sorted[i - 1] * (1.0 - 1e-9)) return true;
  }
  return false;
}

using Coefficients = std::array<double, kTerms>;

// sum_k C_ij(k)^2 is quadratic in the coefficients: a^T S a over a = (A_-2, A_-1, A_0, A_1) (the
// rate ramp adds no covariance), S the lag moments of the terms' cross-covariances.
using LagMoments = Eigen::Matrix4d;
using Kernel = Eigen::Vector4d;

// The smooth part of the generalised covariance of the angle per unit coefficient (see the header),
// h in s: white FM, flicker FM, random walk FM. The white PM part, a Kronecker delta, is added at its
// lags apart.
Kernel smooth_generalised_covariance(double h) {
  const double x = std::abs(h);
  if (x == 0.0) return Kernel::Zero();
  return Kernel(0.0, -x / 2.0, x * x * std::log(x) / (4.0 * std::log(2.0)), x * x * x / 4.0);
}

// The lag moments of second differences of spans m_i, m_j samples (see the header), over integer
// lags k. Between the lags where two taps meet, C_ij is smooth (piecewise polynomial, or h^2 ln h):
// each such piece is summed exactly when short, else by a 16-point midpoint rule; the flicker tails
// beyond the taps are summed out to 8 times the span.
LagMoments lag_moments(double t0, std::int64_t m_i, std::int64_t m_j) {
  static constexpr std::array<double, 3> kWeights = {1.0, -2.0, 1.0};
  const double norm = 1.0 / (2.0 * static_cast<double>(m_i) * static_cast<double>(m_j) * t0 * t0);
  const auto smooth = [&](double k) {
    Kernel c = Kernel::Zero();
    for (int p = 0; p < 3; ++p) {
      for (int q = 0; q < 3; ++q) {
        c += kWeights[static_cast<std::size_t>(p)] * kWeights[static_cast<std::size_t>(q)] *
             smooth_generalised_covariance((k + static_cast<double>(q * m_j - p * m_i)) * t0);
      }
    }
    return Kernel(c * norm);
  };
  std::vector<std::int64_t> breaks;
  for (int p = 0; p < 3; ++p) {
    for (int q = 0; q < 3; ++q) breaks.push_back(p * m_i - q * m_j);
  }
  const std::int64_t reach = 16 * (m_i + m_j);
  breaks.push_back(-reach);
  breaks.push_back(reach + 1);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  LagMoments sum = LagMoments::Zero();
  for (std::size_t b = 0; b + 1 < breaks.size(); ++b) {
    const std::int64_t lo = breaks[b];
    const std::int64_t count = breaks[b + 1] - lo;
    if (count <= 16) {
      for (std::int64_t k = lo; k < lo + count; ++k) {
        const Kernel c = smooth(static_cast<double>(k));
        sum += c * c.transpose();
      }
    } else {
      const double step = static_cast<double>(count) / 16.0;
      for (int n = 0; n < 16; ++n) {
        const Kernel c = smooth(static_cast<double>(lo) - 0.5 + (n + 0.5) * step);
        sum += step * c * c.transpose();
      }
    }
  }
  // White PM: C_ij(k) gains w_p w_q norm / 3 per unit A_-2 where k = p m_i - q m_j (Q^2 = A_-2 / 3).
  std::vector<std::pair<std::int64_t, double>> spikes;
  for (int p = 0; p < 3; ++p) {
    for (int q = 0; q < 3; ++q) {
      const std::int64_t k = p * m_i - q * m_j;
      const double c = kWeights[static_cast<std::size_t>(p)] * kWeights[static_cast<std::size_t>(q)] * norm / 3.0;
      const auto found = std::find_if(spikes.begin(), spikes.end(), [k](const auto& spike) { return spike.first == k; });
      if (found == spikes.end()) {
        spikes.emplace_back(k, c);
      } else {
        found->second += c;
      }
    }
  }
  for (const auto& [k, c] : spikes) {
    const Kernel base = smooth(static_cast<double>(k));
    Kernel with_spike = base;
    with_spike(0) += c;
    sum += with_spike * with_spike.transpose() - base * base.transpose();
  }
  return sum;
}

struct PointSet {
  std::vector<double> tau_s;
  std::vector<double> variance;
  std::vector<double> edf;
  std::vector<std::int64_t> spans;  // averaging factors
  // moments[i][j], j <= i: the lag moments of points i and j (empty: the covariance is not built).
  std::vector<std::vector<LagMoments>> moments;
};

// The covariance of the variance estimates of the points under the model a (see the header).
Eigen::MatrixXd model_covariance(const PointSet& points, const Coefficients& a, const NoiseFitOptions& options) {
  const auto n = static_cast<Eigen::Index>(points.tau_s.size());
  const Kernel random_part(a[0], a[1], a[2], a[3]);
  std::vector<double> model;
  for (std::size_t i = 0; i < points.tau_s.size(); ++i) {
    double value = 0.0;
    for (int p = -2; p <= 2; ++p) value += a[static_cast<std::size_t>(p + 2)] * std::pow(points.tau_s[i], p);
    model.push_back(value > 0.0 ? value : points.variance[i]);
  }
  const auto terms = [&](std::size_t i) {
    const auto m = static_cast<std::size_t>(2 * points.spans[i]);
    return options.sample_count > m ? static_cast<double>(options.sample_count - m) : 1.0;
  };
  const auto lag_sum = [&](std::size_t i, std::size_t j) {
    return random_part.dot(points.moments[i][j] * random_part);
  };
  // A point's edf is that of one noise type (the dominant there, the caller's). In a mix each term
  // scatters with its own edf: where quantisation dominates (edf ~ N) white FM's share has ~N/m, and
  // 2 model^2 / edf made the short taus 5-27 times too sure (N's 1-sigma held the truth in 29-34 % of
  // records). Asymptotically the relative variance of a point is 2 sum_k C_ii(k)^2 / (T C_ii(0)^2)
  // (NIST SP 1065 5.3's basis for one type), so 2 model^2 / edf is scaled by that of the random mix
  // over that of its largest term alone, where the mix scatters more; not below 1: the asymptotic
  // ratio is rough where few terms remain, and taken below 1 at the long taus (flicker under a rate
  // random walk) K's 1-sigma held the truth in 57 % of records. (The ramp stays in `model`:
  // deterministic, it still scatters the estimate through its cross term with the noise where few
  // terms remain.)
  std::vector<double> variance(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < variance.size(); ++i) {
    variance[i] = 2.0 * model[i] * model[i] / points.edf[i];
    Kernel dominant = Kernel::Zero();
    double largest = 0.0;
    double random = 0.0;
    for (Eigen::Index p = 0; p < 4; ++p) {
      const double term = random_part(p) * std::pow(points.tau_s[i], static_cast<double>(p) - 2.0);
      random += term;
      if (term > largest) {
        largest = term;
        dominant = Kernel::Zero();
        dominant(p) = random_part(p);
      }
    }
    const double own_dominant = dominant.dot(points.moments[i][i] * dominant);
    const double own = lag_sum(i, i);
    if (largest > 0.0 && own_dominant > 0.0 && own > 0.0) {
      variance[i] *= std::max(1.0, (own / (random * random)) / (own_dominant / (largest * largest)));
    }
  }
  Eigen::MatrixXd covariance(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    const double variance_i = variance[u];
    const double own_i = lag_sum(u, u);
    covariance(i, i) = variance_i;
    for (Eigen::Index j = 0; j < i; ++j) {
      const auto v = static_cast<std::size_t>(j);
      const double variance_j = variance[v];
      const double own_j = lag_sum(v, v);
      const double terms_factor = options.sample_count > 0 ? std::sqrt(terms(u) * terms(v)) / std::max(terms(u), terms(v)) : 1.0;
      const double correlation =
          own_i > 0.0 && own_j > 0.0 ? std::clamp(terms_factor * lag_sum(u, v) / std::sqrt(own_i * own_j), 0.0, 1.0) : 0.0;
      covariance(i, j) = covariance(j, i) = correlation * std::sqrt(variance_i * variance_j);
    }
  }
  return covariance;
}

// One fit over the points: NNLS on the system whitened by the covariance (diagonal from the observed
// points on the first pass, the model's afterwards).
struct Fit {
  Coefficients a{};
  std::vector<bool> free;
  Eigen::MatrixXd whitened_design;  // columns unscaled
  Eigen::VectorXd whitened_observed;
  double chi_squared = 0.0;
  std::size_t degrees_of_freedom = 0;
  double reduced_chi_squared = 0.0;
  bool consistent = false;
};

// The NNLS solution of the whitened system, columns scaled to unit norm so that tau^-2 and tau^2
// over many decades stay well conditioned.
Coefficients solve_non_negative(const Eigen::MatrixXd& design, const Eigen::VectorXd& observed,
                                const std::vector<bool>& allowed, std::vector<bool>& free) {
  const Eigen::VectorXd x = solve_scaled_non_negative(design, observed, allowed, free);
  Coefficients a{};
  for (int j = 0; j < kTerms; ++j) a[static_cast<std::size_t>(j)] = x(j);
  return a;
}

Eigen::MatrixXd design_of(const PointSet& points) {
  Eigen::MatrixXd design(static_cast<Eigen::Index>(points.tau_s.size()), kTerms);
  for (std::size_t i = 0; i < points.tau_s.size(); ++i) {
    for (int p = -2; p <= 2; ++p) design(static_cast<Eigen::Index>(i), p + 2) = std::pow(points.tau_s[i], p);
  }
  return design;
}

// Whitening by the inverse of the Cholesky factor; eigenvalues are floored at 1e-12 of the largest
// (neighbouring taus of a dense grid are almost fully correlated).
void whiten(const Eigen::MatrixXd& covariance, Eigen::MatrixXd& design, Eigen::VectorXd& observed) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(covariance);
  const Eigen::VectorXd values = eigen.eigenvalues().cwiseMax(1e-12 * eigen.eigenvalues().maxCoeff());
  const Eigen::MatrixXd inverse_root =
      values.cwiseSqrt().cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose();
  design = inverse_root * design;
  observed = inverse_root * observed;
}

constexpr int kCovarianceIterations = 3;
// Above this many points the covariance is not built (a dense grid, e.g. "all"; the cost grows as
// the square): diagonal weights, and a warning that the uncertainties are understated.
constexpr std::size_t kMostCorrelatedPoints = 64;
// How much less chi-squared R must leave than K for R to replace K (fit_points): 1, the change of
// one parameter's 1-sigma interval, so that K, a noise term of every gyro, stays unless a ramp fits
// better. Measured on 40 seeds each of 5000 s at 100 Hz, N = 0.1 deg/sqrt(h) with R = 10 deg/h/h
// (A_2 at about 0.3 of its sigma when K is free) or with K = 3 deg/h/sqrt(h) (NoiseTerms.
// RampAndRateRandomWalkAreToldApart): testing R alone, R kept 25 of 40 ramps (K read at z > 2 in
// 15) and K kept in 38 of 40 walks; with a preference of 0, 39 and 28 (R at z > 2 in 6 walks);
// of 1, 37 and 35 (2); of 2, 31 and 37 (0).
constexpr double kRampPreference = 1.0;

std::vector<Eigen::Index> free_columns(const std::vector<bool>& free) {
  std::vector<Eigen::Index> columns;
  for (std::size_t j = 0; j < free.size(); ++j) {
    if (free[j]) columns.push_back(static_cast<Eigen::Index>(j));
  }
  return columns;
}

void set_goodness(Fit& fit, std::size_t points) {
  const Eigen::VectorXd a = Eigen::Map<const Eigen::VectorXd>(fit.a.data(), kTerms);
  fit.chi_squared = (fit.whitened_design * a - fit.whitened_observed).squaredNorm();
  const auto free_count = static_cast<std::size_t>(std::count(fit.free.begin(), fit.free.end(), true));
  fit.degrees_of_freedom = points > free_count ? points - free_count : 0;
  fit.reduced_chi_squared = 0.0;
  fit.consistent = false;
  if (fit.degrees_of_freedom > 0) {
    const auto dof = static_cast<double>(fit.degrees_of_freedom);
    fit.reduced_chi_squared = fit.chi_squared / dof;
    // A reduced chi-squared beyond 3 of its standard deviations sqrt(2 / dof) above 1.
    fit.consistent = fit.reduced_chi_squared <= 1.0 + 3.0 * std::sqrt(2.0 / dof);
  }
}

// The most of the longest taus the automatic fit range drops (fit_noise_terms).
constexpr std::size_t kLongestDropped = 2;

// The fit over the points, then backward elimination of one long-tau term at the covariance of the
// full model. R (A_2) acts only at the long end of the curve, where it trades off against K (A_1);
// left free when the data do not tell it from zero, R biases K through the non-negativity bound.
// When R lies within kSignificance of its 1-sigma uncertainty of zero (or is held there by the
// bound), R's own z says little, since K takes up a ramp's share (the two are strongly correlated):
// one of R and K is held at zero, K only when the fit holding K at zero has a chi-squared less by
// kRampPreference than the fit holding R (both have the same number of free terms, so this is the
// likelihood ratio). Q (A_-2) stays free (the header): holding a weak but real Q at zero moves its
// share of the short-tau variance into N. The covariance is then updated from the final model.
Fit fit_points(const PointSet& points, const NoiseFitOptions& options) {
  const Eigen::MatrixXd design = design_of(points);
  const Eigen::VectorXd observed = Eigen::Map<const Eigen::VectorXd>(points.variance.data(), design.rows());
  Fit fit;
  std::vector<bool> allowed(kTerms, true);
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(design.rows(), design.rows());
  for (Eigen::Index i = 0; i < design.rows(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    covariance(i, i) = 2.0 * points.variance[k] * points.variance[k] / points.edf[k];
  }
  const bool correlated = !points.moments.empty();
  const auto solve = [&] {
    fit.whitened_design = design;
    fit.whitened_observed = observed;
    whiten(covariance, fit.whitened_design, fit.whitened_observed);
    fit.a = solve_non_negative(fit.whitened_design, fit.whitened_observed, allowed, fit.free);
  };
  const auto iterate = [&] {
    for (int pass = 0; pass < kCovarianceIterations && correlated; ++pass) {
      covariance = model_covariance(points, fit.a, options);
      solve();
    }
  };
  solve();
  iterate();
  set_goodness(fit, points.tau_s.size());
  const std::vector<Eigen::Index> columns = free_columns(fit.free);
  // R held at zero by the bound is not measured either.
  bool ramp_measured = false;
  if (fit.free[kRateRamp] && columns.size() > 1) {
    const auto e = std::find(columns.begin(), columns.end(), static_cast<Eigen::Index>(kRateRamp)) - columns.begin();
    const double sigma =
        std::sqrt(std::max(1.0, fit.reduced_chi_squared) * coefficient_covariance(fit.whitened_design, columns)(e, e));
    ramp_measured = fit.a[kRateRamp] >= kSignificance * sigma;
  }
  if (!ramp_measured && columns.size() > 1) {
    // The fit's chi-squared with the term held at zero, on the current whitened system.
    const auto chi_squared_without = [&](std::size_t term) {
      std::vector<bool> without = allowed;
      without[term] = false;
      std::vector<bool> free;
      const Coefficients a = solve_non_negative(fit.whitened_design, fit.whitened_observed, without, free);
      return (fit.whitened_design * Eigen::Map<const Eigen::VectorXd>(a.data(), kTerms) - fit.whitened_observed)
          .squaredNorm();
    };
    const bool ramp_fits_better =
        chi_squared_without(kRateRandomWalk) + kRampPreference < chi_squared_without(kRateRamp);
    allowed[ramp_fits_better ? kRateRandomWalk : kRateRamp] = false;
    fit.a = solve_non_negative(fit.whitened_design, fit.whitened_observed, allowed, fit.free);
  }
  iterate();
  set_goodness(fit, points.tau_s.size());
  return fit;
}

PointSet points_between(const PointSet& all, std::size_t first, std::size_t last) {
  PointSet points;
  for (std::size_t i = first; i <= last; ++i) {
    points.tau_s.push_back(all.tau_s[i]);
    points.variance.push_back(all.variance[i]);
    points.edf.push_back(all.edf[i]);
    points.spans.push_back(all.spans[i]);
    if (!all.moments.empty()) {
      points.moments.emplace_back(all.moments[i].begin() + static_cast<std::ptrdiff_t>(first),
                                  all.moments[i].begin() + static_cast<std::ptrdiff_t>(i + 1));
    }
  }
  return points;
}

std::string tau_text(double tau) { return fmt::format("{:g} s", tau); }

// The log-log slope of the pair (i, i + 1) and its 1-sigma uncertainty (see the header).
struct PairSlope {
  double slope = 0.0;
  double uncertainty = 0.0;
  bool resolved() const { return uncertainty <= kSlopeResolution; }
};

PairSlope pair_slope(std::span<const double> tau_s, std::span<const double> deviation, std::span<const double> edf,
                     std::size_t i) {
  const double spacing = std::log(tau_s[i + 1] / tau_s[i]);
  return {std::log(deviation[i + 1] / deviation[i]) / spacing,
          std::sqrt(1.0 / (2.0 * edf[i]) + 1.0 / (2.0 * edf[i + 1])) / spacing};
}

// B = sigma / 0.664 at the floor: the least point of the resolved pairs, when a resolved pair beside
// it has a slope within kSlopeTolerance of 0 (IEEE 952 C.1: the flat part at the bottom of the curve).
void read_floor(SlopeReadOff& result, std::span<const double> tau_s, std::span<const double> deviation,
                std::span<const double> edf, const FigureUnits& units) {
  std::vector<bool> in_resolved_pair(tau_s.size(), false);
  for (std::size_t i = 0; i + 1 < tau_s.size(); ++i) {
    if (pair_slope(tau_s, deviation, edf, i).resolved()) in_resolved_pair[i] = in_resolved_pair[i + 1] = true;
  }
  std::optional<std::size_t> floor;
  for (std::size_t i = 0; i < tau_s.size(); ++i) {
    if (in_resolved_pair[i] && (!floor || deviation[i] < deviation[*floor])) floor = i;
  }
  const std::string what = "slope read-off: bias instability B not identified";
  if (!floor) {
    result.warnings.push_back(what + ": no resolved pair of points on the curve");
    return;
  }
  const std::size_t i = *floor;
  // The pairs (i - 1, i) and (i, i + 1), those that exist and are resolved: one flat, and the slope
  // turning across the floor by at most kFloorTurn. Any minimum has a pair near 0 on one side: the
  // bottom of the valley between angle and rate random walk, with no flicker at all, was read as
  // B = 0.118 deg/h (0.114 from sqrt(2 N K / sqrt(3)) / 0.664). There the slope turns by 1/2 sech^2
  // over the spacing, about 0.3 an octave; over a flicker floor it turns less (a real MEMS gyro's:
  // -0.08 to +0.11 an octave, data/real_mems).
  std::optional<double> flattest;
  std::optional<double> before;
  std::optional<double> after;
  for (std::size_t pair = i > 0 ? i - 1 : i; pair <= i && pair + 1 < tau_s.size(); ++pair) {
    const PairSlope s = pair_slope(tau_s, deviation, edf, pair);
    if (!s.resolved()) continue;
    (pair < i ? before : after) = s.slope;
    if (!flattest || std::abs(s.slope) < std::abs(*flattest)) flattest = s.slope;
  }
  if (!flattest || std::abs(*flattest) > kSlopeTolerance) {
    result.warnings.push_back(fmt::format(
        "{}: the curve's floor at tau = {:g} s is not flat (slope beside it {:+.2f}, tolerance {:g}){}", what,
        tau_s[i], flattest.value_or(std::numeric_limits<double>::quiet_NaN()), kSlopeTolerance,
        i + 1 == tau_s.size() || !in_resolved_pair[std::min(i + 1, tau_s.size() - 1)] ? ": the curve is still falling"
                                                                                     : ""));
    return;
  }
  // The turn per octave between the two pairs' centres (on a grid of 5 a decade a valley turns by 0.2
  // a pair, and was read as B in 68 of 100 records).
  const double octaves = i > 0 && i + 1 < tau_s.size() ? std::log2(tau_s[i + 1] / tau_s[i - 1]) / 2.0 : 1.0;
  if (before && after && (*after - *before) / octaves > kFloorTurn) {
    result.warnings.push_back(fmt::format(
        "{}: the curve turns at tau = {:g} s from slope {:+.2f} to {:+.2f} ({:.2f} an octave, more than {:g}): "
        "more like the bottom of a valley between the white and the random-walk noise than a flat floor",
        what, tau_s[i], *before, *after, (*after - *before) / octaves, kFloorTurn));
    return;
  }
  SlopeReading& reading = result.bias_instability;
  reading.tau_s = tau_s[i];
  reading.slope = *flattest;
  const double value = deviation[i] / kBiasInstabilityFactor;
  reading.figure = Figure{value, units.computed, value / std::sqrt(2.0 * edf[i])}.in(units.reported);
}

// lag_moments depends on t0 and the two spans only, and the channels of one record (issue 19), fitted
// side by side, share their tau grid: each (t0, m_i, m_j) is computed once per process. Deterministic,
// so a channel's fit is the same whether it comes first or not.
LagMoments shared_lag_moments(double t0, std::int64_t m_i, std::int64_t m_j) {
  static std::mutex mutex;
  static std::map<std::tuple<double, std::int64_t, std::int64_t>, LagMoments> known;
  constexpr std::size_t kMostKept = 1 << 16;  // a long Python session fitting many grids stays bounded
  const std::lock_guard lock(mutex);
  if (known.size() >= kMostKept) known.clear();
  const auto [entry, added] = known.try_emplace({t0, m_i, m_j});
  if (added) entry->second = lag_moments(t0, m_i, m_j);
  return entry->second;
}

}  // namespace

SensorKind sensor_kind_of(const std::string& input_unit) {
  const Dimension dimension = Unit::parse(input_unit).dimension();
  if (dimension == Unit::parse("rad/s").dimension()) return SensorKind::kGyro;
  if (dimension == Unit::parse("m/s^2").dimension()) return SensorKind::kAccelerometer;
  return SensorKind::kOther;
}

const std::array<NoiseTermName, 5>& noise_term_names(SensorKind kind) {
  // IEEE Std 952-1997 C.1 (gyro); IEEE Std 1293-1998 names the accelerometer's terms for the
  // velocity its output integrates to.
  static constexpr std::array<NoiseTermName, 5> kGyro = {
      NoiseTermName{"quantization", "quantization Q"}, NoiseTermName{"angle_random_walk", "angle random walk N"},
      NoiseTermName{"bias_instability", "bias instability B"}, NoiseTermName{"rate_random_walk", "rate random walk K"},
      NoiseTermName{"rate_ramp", "rate ramp R"}};
  static constexpr std::array<NoiseTermName, 5> kAccelerometer = {
      NoiseTermName{"quantization", "velocity quantization Q"},
      NoiseTermName{"velocity_random_walk", "velocity random walk N"},
      NoiseTermName{"bias_instability", "bias instability B"},
      NoiseTermName{"acceleration_random_walk", "acceleration random walk K"},
      NoiseTermName{"acceleration_ramp", "acceleration ramp R"}};
  return kind == SensorKind::kAccelerometer ? kAccelerometer : kGyro;
}

void NoiseFitOptions::validate() const {
  if (fit_range && !(fit_range->tau_min_s > 0.0 && fit_range->tau_min_s <= fit_range->tau_max_s &&
                     std::isfinite(fit_range->tau_max_s))) {
    throw Error(fmt::format("the fit range needs 0 < TMIN <= TMAX (got {}:{})", fit_range->tau_min_s,
                            fit_range->tau_max_s));
  }
  if (!(sample_interval_s >= 0.0) || !std::isfinite(sample_interval_s)) {
    throw Error("the sample interval must be positive and finite");
  }
}

FitRange parse_fit_range(const std::string& text) {
  const auto colon = text.find(':');
  const auto number = [&](const std::string& part) {
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != part.size()) {
      throw Error(fmt::format("the fit range must read TMIN:TMAX in s (got '{}')", text));
    }
    return value;
  };
  if (colon == std::string::npos) throw Error(fmt::format("the fit range must read TMIN:TMAX in s (got '{}')", text));
  NoiseFitOptions options;
  options.fit_range = FitRange{number(text.substr(0, colon)), number(text.substr(colon + 1))};
  options.validate();
  return *options.fit_range;
}

NoiseTerms fit_noise_terms(std::span<const double> tau_s, std::span<const double> variance,
                           std::span<const double> edf, const std::string& input_unit, const NoiseFitOptions& options) {
  check_points(tau_s, variance, edf);
  options.validate();
  const double t0 = options.sample_interval_s > 0.0 ? options.sample_interval_s
                                                    : *std::min_element(tau_s.begin(), tau_s.end());
  // The fit runs with t0 as its unit of time (taus of 1, 2, 4 ...), and its coefficients A_p are
  // turned back into seconds by t0^-p: in seconds, taus far from 1 s (a rate of 1e-100 Hz) gave
  // columns tau^-2 and tau^2 so unlike that the fit lost 7 % of N.
  PointSet all;
  for (double tau : tau_s) all.tau_s.push_back(tau / t0);
  // The fit runs on the variances divided by the largest: the model is linear in its coefficients,
  // so they and their uncertainties are the scaled fit's times `scale`, and the covariance of the
  // points (of the order of the squared variances) neither overflows nor underflows for records of
  // any magnitude (1e45 deg/h gave covariances beyond the range of a double and a failed QR).
  const double scale = *std::max_element(variance.begin(), variance.end());
  if (!(scale > 0.0) || !std::isfinite(scale)) {
    throw Error(fmt::format("the noise fit needs finite, positive variances (largest {:g})", scale));
  }
  for (double v : variance) all.variance.push_back(v / scale);
  all.edf.assign(edf.begin(), edf.end());
  for (double tau : tau_s) all.spans.push_back(std::max<std::int64_t>(1, std::llround(tau / t0)));
  if (tau_s.size() <= kMostCorrelatedPoints) {
    for (std::size_t i = 0; i < tau_s.size(); ++i) {
      all.moments.emplace_back();
      for (std::size_t j = 0; j <= i; ++j) all.moments[i].push_back(shared_lag_moments(1.0, all.spans[i], all.spans[j]));
    }
  }
  NoiseTerms terms;
  if (all.moments.empty()) {
    terms.warnings.push_back(fmt::format(
        "noise fit: {} taus, more than {}: the correlation of the overlapping estimates is not modelled and the "
        "uncertainties are understated; use a sparser tau grid (e.g. octave)",
        tau_s.size(), kMostCorrelatedPoints));
  } else if (closer_than_an_octave(tau_s)) {
    // The correlation model is validated on octave grids (the Monte Carlo test): on eight points an
    // octave, 6000 white-noise samples gave an angle random walk 3.3 % off the truth with a 0.6 %
    // uncertainty. allan_variance fits on the taus an octave or more apart for that reason.
    terms.warnings.push_back(
        "noise fit: taus closer than an octave: the correlation model of the overlapping estimates is "
        "validated on octave grids and the uncertainties may be understated; fit on taus an octave or more apart");
  }
  std::size_t first = 0;
  std::size_t last = tau_s.size() - 1;
  Fit fit;
  if (options.fit_range) {
    // The taus inside the range, within a relative 1e-9 (a range typed from printed taus).
    const auto inside = [&](double tau) {
      return tau >= options.fit_range->tau_min_s * (1.0 - 1e-9) && tau <= options.fit_range->tau_max_s * (1.0 + 1e-9);
    };
    std::vector<std::size_t> kept;
    for (std::size_t i = 0; i < tau_s.size(); ++i) {
      if (inside(tau_s[i])) kept.push_back(i);
    }
    if (kept.size() < 2) {
      throw Error(fmt::format("the fit range {}:{} s holds {} of the curve's taus; the fit needs at least 2",
                              options.fit_range->tau_min_s, options.fit_range->tau_max_s, kept.size()));
    }
    first = kept.front();
    last = kept.back();
    fit = fit_points(points_between(all, first, last), options);
    terms.fit_range_chosen_by = "user";
    terms.fit_range_reason = "given by the user";
  } else {
    // Drop the fewest taus that make the fit consistent, keeping at least kTerms + 1 points (one
    // degree of freedom with every term free): the shortest first, where the model fails by design
    // (an anti-alias filter, quantisation), and, at the same count, up to kLongestDropped of the
    // longest, whose few degrees of freedom let a random walk's excursion break every range that
    // keeps them (dropping from the short end only, one such record was trimmed to 204.8 s and read
    // N at 3 times the truth). If none is consistent, keep the least inconsistent.
    fit = fit_points(points_between(all, first, last), options);
    const double full_reduced_chi_squared = fit.reduced_chi_squared;
    Fit best = fit;
    std::size_t best_first = first;
    std::size_t best_last = last;
    for (std::size_t dropped = 1; !best.consistent && last + 1 - dropped >= kTerms + 1; ++dropped) {
      for (std::size_t longest = 0; !best.consistent && longest <= std::min(dropped, kLongestDropped); ++longest) {
        const std::size_t start = dropped - longest;
        const std::size_t end = last - longest;
        Fit trial = fit_points(points_between(all, start, end), options);
        if (trial.consistent || trial.reduced_chi_squared < best.reduced_chi_squared) {
          best = std::move(trial);
          best_first = start;
          best_last = end;
        }
      }
    }
    first = best_first;
    last = best_last;
    fit = std::move(best);
    terms.fit_range_chosen_by = "automatic";
    if (first == 0 && last + 1 == tau_s.size()) {
      // No degree of freedom left: nothing says whether the model fits (the verdict is undetermined).
      terms.fit_range_reason = fit.degrees_of_freedom == 0 ? "the whole curve: no degree of freedom left, no test of the fit"
                               : fit.consistent            ? "the whole curve: the model fits it"
                                                           : "the whole curve: no shorter range fits better";
    } else if (last + 1 == tau_s.size()) {
      terms.fit_range_reason = fmt::format(
          "taus below {} dropped: the model does not hold there (anti-alias filter or quantisation at short tau); "
          "reduced chi-squared {:.3g} over the whole curve, {:.3g} from {}",
          tau_text(tau_s[first]), full_reduced_chi_squared, fit.reduced_chi_squared, tau_text(tau_s[first]));
    } else {
      terms.fit_range_reason = fmt::format(
          "{}taus above {} dropped: the model does not hold over the whole curve (reduced chi-squared {:.3g}), and the "
          "longest taus, of few degrees of freedom, broke every range keeping them; {:.3g} from {} to {}",
          first == 0 ? "" : fmt::format("taus below {} and ", tau_text(tau_s[first])), tau_text(tau_s[last]),
          full_reduced_chi_squared, fit.reduced_chi_squared, tau_text(tau_s[first]), tau_text(tau_s[last]));
    }
  }
  terms.fit_range = FitRange{tau_s[first], tau_s[last]};
  const PointSet fitted = points_between(all, first, last);
  terms.reduced_chi_squared = fit.reduced_chi_squared;
  terms.degrees_of_freedom = fit.degrees_of_freedom;
  terms.verdict = fit.degrees_of_freedom == 0 ? "undetermined" : fit.consistent ? "consistent" : "inconsistent";
  if (fit.degrees_of_freedom == 0) {
    terms.warnings.push_back("noise fit: no degree of freedom left over the fit range: how well the model fits is unknown");
  } else if (!fit.consistent) {
    terms.warnings.push_back(fmt::format(
        "noise fit: the model of GJB eq. (30) does not fit the curve from {} to {} (reduced chi-squared {:.3g} over {} "
        "degrees of freedom): its figures are doubtful; try --fit-range",
        tau_text(terms.fit_range.tau_min_s), tau_text(terms.fit_range.tau_max_s), fit.reduced_chi_squared,
        fit.degrees_of_freedom));
  }
  const double inflation = std::max(1.0, fit.reduced_chi_squared);
  const std::vector<Eigen::Index> columns = free_columns(fit.free);
  const Eigen::MatrixXd free_covariance = coefficient_covariance(fit.whitened_design, columns);
  const double b_factor = 1.0 / (kBiasInstabilityFactor * kBiasInstabilityFactor);
  struct TermSpec {
    Figure NoiseTerms::*figure;
    double c;
    FigureUnits units;
  };
  const std::array<TermSpec, kTerms> specs = {
      TermSpec{&NoiseTerms::quantization, 1.0 / 3.0, units_for(input_unit, -2)},
      TermSpec{&NoiseTerms::angle_random_walk, 1.0, units_for(input_unit, -1)},
      TermSpec{&NoiseTerms::bias_instability, b_factor, units_for(input_unit, 0)},
      TermSpec{&NoiseTerms::rate_random_walk, 3.0, units_for(input_unit, 1)},
      TermSpec{&NoiseTerms::rate_ramp, 2.0, units_for(input_unit, 2)}};
  for (Eigen::Index j = 0; j < kTerms; ++j) {
    const auto k = static_cast<std::size_t>(j);
    const double to_seconds = scale * std::pow(t0, static_cast<double>(2 - j));  // A_p = scale * a_p * t0^-p
    terms.coefficients[k] = to_seconds * fit.a[k];
    const TermSpec& spec = specs[k];
    const auto place = std::find(columns.begin(), columns.end(), j);
    terms.identified[k] = place != columns.end();
    if (terms.identified[k]) {
      const auto c = place - columns.begin();
      terms.coefficient_uncertainties[k] = to_seconds * std::sqrt(inflation * free_covariance(c, c));
      terms.*spec.figure = figure_of(terms.coefficients[k], terms.coefficient_uncertainties[k], spec.c, spec.units);
      terms.significant[k] = terms.coefficients[k] >= kSignificance * terms.coefficient_uncertainties[k];
      if (terms.significant[k]) continue;
    }
    // Held at zero, or within 2 sigma of it: an upper bound. Freed (last) along with the other free
    // ones, its unconstrained estimate and uncertainty give the bound. The covariance of the points
    // depends on the model, and one with the term at or near zero understates the scatter the term
    // would bring: the bound is recomputed under the model that holds the term at its bound until it
    // settles (at most kCovarianceIterations times).
    std::vector<Eigen::Index> with_it;
    std::copy_if(columns.begin(), columns.end(), std::back_inserter(with_it), [j](Eigen::Index c) { return c != j; });
    with_it.push_back(j);
    const auto bound_under = [&](const Eigen::MatrixXd& whitened_design, const Eigen::VectorXd& whitened_observed) {
      Eigen::MatrixXd sub(whitened_design.rows(), static_cast<Eigen::Index>(with_it.size()));
      for (std::size_t c = 0; c < with_it.size(); ++c) sub.col(static_cast<Eigen::Index>(c)) = whitened_design.col(with_it[c]);
      const Eigen::MatrixXd joint = coefficient_covariance(whitened_design, with_it);
      const Eigen::VectorXd unconstrained = joint * (sub.transpose() * whitened_observed);
      const Eigen::Index last_column = joint.rows() - 1;
      const double sigma = std::sqrt(inflation * joint(last_column, last_column));
      return std::pair{sigma, std::max(0.0, unconstrained(last_column)) + kSignificance * sigma};
    };
    auto [sigma, bound] = bound_under(fit.whitened_design, fit.whitened_observed);
    for (int pass = 0; pass < kCovarianceIterations && !fitted.moments.empty(); ++pass) {
      Coefficients at_bound = fit.a;
      at_bound[k] = bound;
      Eigen::MatrixXd design = design_of(fitted);
      Eigen::VectorXd observed = Eigen::Map<const Eigen::VectorXd>(fitted.variance.data(), design.rows());
      whiten(model_covariance(fitted, at_bound, options), design, observed);
      const auto [next_sigma, next_bound] = bound_under(design, observed);
      const bool settled = std::abs(next_bound - bound) <= 0.01 * bound;
      sigma = next_sigma;
      bound = next_bound;
      if (settled) break;
    }
    terms.upper_bounds[k] = figure_of(to_seconds * bound, std::numeric_limits<double>::quiet_NaN(), spec.c, spec.units);
    if (!terms.identified[k]) {
      terms.coefficient_uncertainties[k] = to_seconds * sigma;
      terms.*spec.figure = figure_of(0.0, std::numeric_limits<double>::quiet_NaN(), spec.c, spec.units);
    }
  }
  return terms;
}

nlohmann::json NoiseTerms::to_json(const std::string& input_unit) const {
  nlohmann::json coefficients_json = nlohmann::json::array();
  for (int p = -2; p <= 2; ++p) {
    const auto k = static_cast<std::size_t>(p + 2);
    // fmt rather than string concatenation: GCC 12 gives a false -Wrestrict for "^" + to_string(p).
    const std::string unit = fmt::format("({})^2*s{}", input_unit, p == 1 ? std::string() : fmt::format("^{}", p));
    coefficients_json.push_back({{"power", p},
                                 {"value", coefficients[k]},
                                 {"uncertainty", coefficient_uncertainties[k]},
                                 {"identified", identified[k]},
                                 {"significant", significant[k]},
                                 {"unit", p == 0 ? "(" + input_unit + ")^2" : unit}});
  }
  const auto figure = [&](const Figure& f, int p) {
    const auto k = static_cast<std::size_t>(p + 2);
    return noise_figure_json(f, identified[k], significant[k], upper_bounds[k]);
  };
  const SensorKind kind = sensor_kind_of(input_unit);
  const auto& names = noise_term_names(kind);
  nlohmann::json json = {{names[0].key, figure(quantization, -2)},
                         {names[1].key, figure(angle_random_walk, -1)},
                         {names[2].key, figure(bias_instability, 0)},
                         {names[3].key, figure(rate_random_walk, 1)},
                         {names[4].key, figure(rate_ramp, 2)}};
  // GJB 2426A eq. (31) is a gyro's: RWC is N.
  if (kind != SensorKind::kAccelerometer) json["random_walk_coefficient"] = figure(angle_random_walk, -1);
  json.update(nlohmann::json{{"fit",
           {{"model",
             "sigma^2(tau) = sum_{p=-2..2} A_p tau^p (GJB 2426A eq. 30), non-negative generalised least squares "
             "(covariance of the overlapping estimates from the fitted model)"},
            {"coefficients", coefficients_json},
            {"reduced_chi_squared", reduced_chi_squared},
            {"degrees_of_freedom", degrees_of_freedom},
            {"verdict", verdict},
            {"fit_range",
             {{"tau_min_s", fit_range.tau_min_s},
              {"tau_max_s", fit_range.tau_max_s},
              {"chosen_by", fit_range_chosen_by},
              {"reason", fit_range_reason}}}}}});
  return json;
}

SlopeReadOff read_noise_slopes(std::span<const double> tau_s, std::span<const double> deviation,
                               std::span<const double> edf, const std::string& input_unit) {
  check_points(tau_s, deviation, edf);
  SlopeReadOff result;
  // Among the resolved pairs within tolerance, the one whose slope is closest to the target
  // (MATLAB: min(abs(dlogadev - slope))).
  const auto read = [&](double target, const std::string& name, SlopeReading& reading, double tau_power,
                        double factor, const FigureUnits& units) {
    std::optional<std::size_t> best;
    double best_distance = std::numeric_limits<double>::infinity();
    std::optional<double> closest_slope;  // among the resolved pairs
    for (std::size_t i = 0; i + 1 < tau_s.size(); ++i) {
      const auto [slope, uncertainty] = pair_slope(tau_s, deviation, edf, i);
      const double distance = std::abs(slope - target);
      if (uncertainty > kSlopeResolution) continue;
      if (!closest_slope || distance < std::abs(*closest_slope - target)) closest_slope = slope;
      if (distance <= kSlopeTolerance && distance < best_distance) {
        best_distance = distance;
        best = i;
        reading.slope = slope;
      }
    }
    if (!best) {
      result.warnings.push_back(fmt::format(
          "slope read-off: no region of slope {:+g} (within {:g}, resolved to {:g}) on the curve{}: {} not identified",
          target, kSlopeTolerance, kSlopeResolution,
          closest_slope ? fmt::format(" (closest resolved slope {:+.2f})", *closest_slope) : "",
          name));
      return;
    }
    const std::size_t i = *best;
    reading.tau_s = tau_s[i];
    const double value = deviation[i] * factor * std::pow(tau_s[i], tau_power);
    reading.figure = Figure{value, units.computed, value / std::sqrt(2.0 * edf[i])}.in(units.reported);
  };
  // sigma = N / sqrt(tau): N = sigma(tau) sqrt(tau), the -1/2 line at tau = 1 s.
  const auto& names = noise_term_names(sensor_kind_of(input_unit));
  read(-0.5, std::string(names[1].label), result.angle_random_walk, 0.5, 1.0, units_for(input_unit, -1));
  read_floor(result, tau_s, deviation, edf, units_for(input_unit, 0));
  // sigma = K sqrt(tau / 3): K = sigma(tau) sqrt(3 / tau), the +1/2 line at tau = 3 s.
  read(0.5, std::string(names[3].label), result.rate_random_walk, -0.5, std::sqrt(3.0), units_for(input_unit, 1));
  return result;
}

nlohmann::json SlopeReadOff::to_json(const std::string& input_unit) const {
  const auto figure = [](const SlopeReading& r) { return r.figure ? nlohmann::json(*r.figure) : nlohmann::json(nullptr); };
  const auto tau = [](const SlopeReading& r) { return r.figure ? nlohmann::json(r.tau_s) : nlohmann::json(nullptr); };
  const auto& names = noise_term_names(sensor_kind_of(input_unit));
  const auto key = [](std::string_view name, std::string_view suffix) { return std::string(name) + std::string(suffix); };
  return {{"method", "log-log slope read-off on OADEV (MATLAB allanvar example); null: no region of that slope"},
          {key(names[1].key, ""), figure(angle_random_walk)},
          {key(names[1].key, "_tau_s"), tau(angle_random_walk)},
          {key(names[2].key, ""), figure(bias_instability)},
          {key(names[2].key, "_tau_s"), tau(bias_instability)},
          {key(names[3].key, ""), figure(rate_random_walk)},
          {key(names[3].key, "_tau_s"), tau(rate_random_walk)},
          {"slope_tolerance", kSlopeTolerance},
          {"slope_resolution", kSlopeResolution}};
}

}  // namespace inertest

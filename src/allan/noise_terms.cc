#include "inertest/allan/noise_terms.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/units.h"

namespace inertest {
namespace {

constexpr int kTerms = 5;  // p = -2..2

bool is_angular_rate(const std::string& unit) {
  return Unit::parse(unit).dimension() == Unit::parse("rad/s").dimension();
}

// The unit a figure is computed in from the input unit U, and the unit it is reported in.
struct FigureUnits {
  std::string computed;
  std::string reported;
};

FigureUnits units_for(const std::string& input_unit, const std::string& suffix, const std::string& angular) {
  const std::string computed = suffix.empty() ? input_unit : "(" + input_unit + ")" + suffix;
  return {computed, is_angular_rate(input_unit) ? angular : computed};
}

// value = sqrt(c A); 1-sigma by first order, or the bound's figure for A = 0.
Figure figure_of(double coefficient, double uncertainty, double c, const FigureUnits& units) {
  Figure figure;
  figure.unit = units.computed;
  figure.value = std::sqrt(c * std::max(0.0, coefficient));
  if (std::isfinite(uncertainty)) {
    figure.uncertainty = coefficient > 0.0 ? std::sqrt(c) * uncertainty / (2.0 * std::sqrt(coefficient))
                                           : std::sqrt(c * uncertainty);
  }
  return figure.in(units.reported);
}

// Lawson-Hanson NNLS: min ||A x - b|| subject to x >= 0. Returns x and the free set.
Eigen::VectorXd non_negative_least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                                           std::vector<bool>& free) {
  const Eigen::Index n = a.cols();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  free.assign(static_cast<std::size_t>(n), false);
  const double tolerance = 1e-12 * a.norm() * std::max(1.0, b.norm());
  for (int outer = 0; outer < 3 * kTerms * kTerms; ++outer) {
    const Eigen::VectorXd gradient = a.transpose() * (b - a * x);
    Eigen::Index best = -1;
    for (Eigen::Index j = 0; j < n; ++j) {
      if (!free[static_cast<std::size_t>(j)] && gradient(j) > tolerance && (best < 0 || gradient(j) > gradient(best))) {
        best = j;
      }
    }
    if (best < 0) break;
    free[static_cast<std::size_t>(best)] = true;
    for (int inner = 0; inner < 3 * kTerms; ++inner) {
      std::vector<Eigen::Index> columns;
      for (Eigen::Index j = 0; j < n; ++j) {
        if (free[static_cast<std::size_t>(j)]) columns.push_back(j);
      }
      Eigen::MatrixXd sub(a.rows(), static_cast<Eigen::Index>(columns.size()));
      for (std::size_t c = 0; c < columns.size(); ++c) sub.col(static_cast<Eigen::Index>(c)) = a.col(columns[c]);
      const Eigen::VectorXd solution = sub.colPivHouseholderQr().solve(b);
      Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
      for (std::size_t c = 0; c < columns.size(); ++c) z(columns[c]) = solution(static_cast<Eigen::Index>(c));
      bool feasible = true;
      double step = 1.0;
      for (Eigen::Index j : columns) {
        if (z(j) <= 0.0) {
          feasible = false;
          step = std::min(step, x(j) / (x(j) - z(j)));
        }
      }
      if (feasible) {
        x = z;
        break;
      }
      x += step * (z - x);
      for (Eigen::Index j : columns) {
        if (x(j) <= 1e-15 * std::max(1.0, x.cwiseAbs().maxCoeff())) {
          x(j) = 0.0;
          free[static_cast<std::size_t>(j)] = false;
        }
      }
    }
  }
  return x;
}

void check_points(std::span<const double> tau_s, std::span<const double> values, std::span<const double> edf) {
  if (tau_s.size() != values.size() || tau_s.size() != edf.size()) throw Error("tau, values and edf differ in length");
  if (tau_s.size() < 2) throw Error("noise identification needs at least 2 averaging times");
  for (std::size_t i = 0; i < tau_s.size(); ++i) {
    if (!(tau_s[i] > 0.0) || !(values[i] > 0.0) || !(edf[i] > 0.0)) {
      throw Error("noise identification needs positive tau, deviations and edf (point " + std::to_string(i + 1) + ")");
    }
  }
}

}  // namespace

NoiseTerms fit_noise_terms(std::span<const double> tau_s, std::span<const double> variance,
                           std::span<const double> edf, const std::string& input_unit) {
  check_points(tau_s, variance, edf);
  const auto rows = static_cast<Eigen::Index>(tau_s.size());
  // Rows weighted by sqrt(edf/2)/sigma^2 (1 / standard deviation of the variance estimate), columns
  // scaled to unit norm so that tau^-2 and tau^2 over many decades stay well conditioned.
  Eigen::MatrixXd design(rows, kTerms);
  Eigen::VectorXd observed(rows);
  for (Eigen::Index i = 0; i < rows; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double row_weight = std::sqrt(edf[k] / 2.0) / variance[k];
    for (int p = -2; p <= 2; ++p) design(i, p + 2) = row_weight * std::pow(tau_s[k], p);
    observed(i) = row_weight * variance[k];
  }
  Eigen::VectorXd column_scale(kTerms);
  for (int j = 0; j < kTerms; ++j) {
    column_scale(j) = design.col(j).norm();
    design.col(j) /= column_scale(j);
  }
  std::vector<bool> free;
  const Eigen::VectorXd scaled = non_negative_least_squares(design, observed, free);

  NoiseTerms terms;
  const double residual = (design * scaled - observed).squaredNorm();
  const auto free_count = static_cast<Eigen::Index>(std::count(free.begin(), free.end(), true));
  const double dof = static_cast<double>(rows - free_count);
  terms.reduced_chi_squared = dof > 0.0 ? residual / dof : 0.0;
  const double inflation = std::max(1.0, terms.reduced_chi_squared);
  // Covariance of the free coefficients; a coefficient at zero takes its variance from the whole
  // normal matrix (as if it were free).
  std::vector<Eigen::Index> columns;
  for (Eigen::Index j = 0; j < kTerms; ++j) {
    if (free[static_cast<std::size_t>(j)]) columns.push_back(j);
  }
  Eigen::MatrixXd sub(rows, static_cast<Eigen::Index>(columns.size()));
  for (std::size_t c = 0; c < columns.size(); ++c) sub.col(static_cast<Eigen::Index>(c)) = design.col(columns[c]);
  const Eigen::MatrixXd free_covariance = (sub.transpose() * sub).completeOrthogonalDecomposition().pseudoInverse();
  const Eigen::MatrixXd normal = design.transpose() * design;
  const Eigen::FullPivLU<Eigen::MatrixXd> normal_lu(normal);
  const Eigen::MatrixXd full_covariance =
      normal_lu.isInvertible()
          ? Eigen::MatrixXd(normal_lu.inverse())
          : Eigen::MatrixXd::Constant(kTerms, kTerms, std::numeric_limits<double>::infinity());
  for (int j = 0; j < kTerms; ++j) {
    const auto k = static_cast<std::size_t>(j);
    terms.coefficients[k] = scaled(j) / column_scale(j);
    double variance_scaled = full_covariance(j, j);
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (columns[c] == j) variance_scaled = free_covariance(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(c));
    }
    terms.coefficient_uncertainties[k] = std::sqrt(inflation * variance_scaled) / column_scale(j);
  }
  const auto& a = terms.coefficients;
  const auto& s = terms.coefficient_uncertainties;
  const double b_factor = 1.0 / (kBiasInstabilityFactor * kBiasInstabilityFactor);
  terms.quantization = figure_of(a[0], s[0], 1.0 / 3.0, units_for(input_unit, "*s", "arcsec"));
  terms.angle_random_walk = figure_of(a[1], s[1], 1.0, units_for(input_unit, "*sqrt(s)", "deg/sqrt(h)"));
  terms.bias_instability = figure_of(a[2], s[2], b_factor, units_for(input_unit, "", "deg/h"));
  terms.rate_random_walk = figure_of(a[3], s[3], 3.0, units_for(input_unit, "/sqrt(s)", "deg/h/sqrt(h)"));
  terms.rate_ramp = figure_of(a[4], s[4], 2.0, units_for(input_unit, "/s", "deg/h/h"));
  for (double tau : tau_s) {
    int best = -2;
    double largest = -1.0;
    for (int p = -2; p <= 2; ++p) {
      const double contribution = a[static_cast<std::size_t>(p + 2)] * std::pow(tau, p);
      if (contribution > largest) {
        largest = contribution;
        best = p;
      }
    }
    terms.dominant_power.push_back(best);
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
                                 {"unit", p == 0 ? "(" + input_unit + ")^2" : unit}});
  }
  return {{"quantization", quantization},
          {"angle_random_walk", angle_random_walk},
          {"random_walk_coefficient", angle_random_walk},
          {"bias_instability", bias_instability},
          {"rate_random_walk", rate_random_walk},
          {"rate_ramp", rate_ramp},
          {"fit",
           {{"model", "sigma^2(tau) = sum_{p=-2..2} A_p tau^p (GJB 2426A eq. 30), weighted non-negative least squares"},
            {"coefficients", coefficients_json},
            {"reduced_chi_squared", reduced_chi_squared}}}};
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
      const double spacing = std::log(tau_s[i + 1] / tau_s[i]);
      const double slope = std::log(deviation[i + 1] / deviation[i]) / spacing;
      const double uncertainty = std::sqrt(1.0 / (2.0 * edf[i]) + 1.0 / (2.0 * edf[i + 1])) / spacing;
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
  read(-0.5, "angle random walk N", result.angle_random_walk, 0.5, 1.0,
       units_for(input_unit, "*sqrt(s)", "deg/sqrt(h)"));
  // The flat part: sigma = 0.664 B.
  read(0.0, "bias instability B", result.bias_instability, 0.0, 1.0 / kBiasInstabilityFactor,
       units_for(input_unit, "", "deg/h"));
  // sigma = K sqrt(tau / 3): K = sigma(tau) sqrt(3 / tau), the +1/2 line at tau = 3 s.
  read(0.5, "rate random walk K", result.rate_random_walk, -0.5, std::sqrt(3.0),
       units_for(input_unit, "/sqrt(s)", "deg/h/sqrt(h)"));
  return result;
}

nlohmann::json SlopeReadOff::to_json() const {
  const auto figure = [](const SlopeReading& r) { return r.figure ? nlohmann::json(*r.figure) : nlohmann::json(nullptr); };
  const auto tau = [](const SlopeReading& r) { return r.figure ? nlohmann::json(r.tau_s) : nlohmann::json(nullptr); };
  return {{"method", "log-log slope read-off on OADEV (MATLAB allanvar example); null: no region of that slope"},
          {"angle_random_walk", figure(angle_random_walk)},
          {"angle_random_walk_tau_s", tau(angle_random_walk)},
          {"bias_instability", figure(bias_instability)},
          {"bias_instability_tau_s", tau(bias_instability)},
          {"rate_random_walk", figure(rate_random_walk)},
          {"rate_random_walk_tau_s", tau(rate_random_walk)},
          {"slope_tolerance", kSlopeTolerance},
          {"slope_resolution", kSlopeResolution}};
}

}  // namespace inertest

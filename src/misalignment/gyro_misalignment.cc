#include "inertest/misalignment/gyro_misalignment.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/io/angle_column.h"
#include "misalignment/misalignment_fit.h"

namespace inertest {
namespace {

using misalignment_detail::arcsec_figure;
using misalignment_detail::cos_deg;
using misalignment_detail::sin_deg;

// Order of the unknowns of (*) in the design; the names are the JSON keys.
enum Angle { kY0, kX0, kY1, kY2, kZ2, kAngleCount };
const std::vector<std::string> kAngleNames = {"delta_theta_y0", "delta_theta_x0", "delta_theta_y1", "delta_theta_y2",
                                              "delta_theta_z2"};

// One position at one |ω| with the rows of its two directions.
struct PositionPair {
  double alpha_deg = 0.0;
  double beta_deg = 0.0;
  double rate_dps = 0.0;  // |ω|
  const GyroMisalignmentRow* plus = nullptr;
  const GyroMisalignmentRow* minus = nullptr;
};

SourceLocation location_of(const GyroMisalignmentOptions& options, const GyroMisalignmentRow& row) {
  return {options.source, row.line, 0};
}

// Positions in radians read as degrees (io/angle_column.h): from a file, a record listing or arrays.
void check_positions_in_degrees(std::span<const GyroMisalignmentRow> rows, const GyroMisalignmentOptions& options) {
  for (const auto& [column, angle_of] :
       {std::pair{"alpha_deg", &GyroMisalignmentRow::alpha_deg}, std::pair{"beta_deg", &GyroMisalignmentRow::beta_deg}}) {
    std::vector<double> angles;
    for (const GyroMisalignmentRow& row : rows) angles.push_back(row.*angle_of);
    if (const std::optional<std::size_t> i = radians_among_degrees(angles)) {
      throw Error(location_of(options, rows[*i]), "gyro misalignment: " + radians_message(column, angles[*i]));
    }
  }
}

std::vector<PositionPair> pair_directions(std::span<const GyroMisalignmentRow> rows,
                                          const GyroMisalignmentOptions& options) {
  std::vector<PositionPair> pairs;
  for (const GyroMisalignmentRow& row : rows) {
    const SourceLocation where = location_of(options, row);
    if (!std::isfinite(row.alpha_deg) || !std::isfinite(row.beta_deg) || !std::isfinite(row.rate_dps) ||
        !std::isfinite(row.output)) {
      throw Error(where, "gyro misalignment: alpha_deg, beta_deg, rate_dps and output must be finite numbers");
    }
    if (row.rate_dps == 0.0) {
      throw Error(where, "gyro misalignment: rate_dps is zero; every row is one direction (+ω or −ω) of the table");
    }
    // A position read again (repeated readings) is another equation: its k-th row at +ω pairs with
    // its k-th at −ω, in the order given.
    const double rate = std::abs(row.rate_dps);
    const bool plus = row.rate_dps > 0.0;
    auto pair = std::find_if(pairs.begin(), pairs.end(), [&](const PositionPair& p) {
      return p.alpha_deg == row.alpha_deg && p.beta_deg == row.beta_deg && p.rate_dps == rate &&
             (plus ? p.plus : p.minus) == nullptr;
    });
    if (pair == pairs.end()) pair = pairs.insert(pairs.end(), PositionPair{row.alpha_deg, row.beta_deg, rate});
    (plus ? pair->plus : pair->minus) = &row;
  }
  for (const PositionPair& pair : pairs) {
    if (pair.plus != nullptr && pair.minus != nullptr) continue;
    const GyroMisalignmentRow& present = pair.plus != nullptr ? *pair.plus : *pair.minus;
    throw Error(location_of(options, present),
                fmt::format("gyro misalignment: alpha {} deg, beta {} deg at {} deg/s has no row at {} deg/s; each "
                            "position needs both directions, the separation uses V(+) − V(−)",
                            pair.alpha_deg, pair.beta_deg, present.rate_dps, -present.rate_dps));
  }
  return pairs;
}

// Solves (*) over the given position pairs; observations in angle units, (V(+) − V(−))/(2·kI·ω).
GyroMisalignmentFit fit_pairs(const std::vector<const PositionPair*>& pairs, const GyroMisalignmentOptions& options,
                              const std::string& what) {
  Matrix design(pairs.size(), kAngleCount);
  std::vector<double> observations(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const PositionPair& p = *pairs[i];
    // (*): V(+) − V(−) = 2·kI·ω·(−Δθy0·cosβ + Δθx0·sinβ − Δθy1 + Δθz2·sinα − Δθy2·cosα).
    design(i, kY0) = -cos_deg(p.beta_deg);
    design(i, kX0) = sin_deg(p.beta_deg);
    design(i, kY1) = -1.0;
    design(i, kY2) = -cos_deg(p.alpha_deg);
    design(i, kZ2) = sin_deg(p.alpha_deg);
    observations[i] = (p.plus->output - p.minus->output) / (2.0 * options.scale_factor * p.rate_dps);
  }
  const LeastSquaresResult solution = misalignment_detail::solve_separating(
      design, observations, kAngleNames, SourceLocation{options.source, 0, 0}, what,
      "the terms -cos(beta), sin(beta), -1, -cos(alpha), sin(alpha) of the five angles must be independent over the "
      "positions, as with the paper's (alpha, beta) = (0,0), (0,180), (180,180), (90,180), (0,90)");

  const bool estimable = solution.degrees_of_freedom > 0;
  auto angle = [&](Angle a) {
    const auto index = static_cast<std::size_t>(a);
    return arcsec_figure(solution.parameters[index],
                         estimable ? std::optional<double>(solution.standard_error(index)) : std::nullopt);
  };
  GyroMisalignmentFit fit;
  fit.angles.delta_theta_y0 = angle(kY0);
  fit.angles.delta_theta_x0 = angle(kX0);
  fit.angles.delta_theta_y1 = angle(kY1);
  fit.angles.delta_theta_y2 = angle(kY2);
  fit.angles.delta_theta_z2 = angle(kZ2);
  std::optional<misalignment_detail::AnglePairCovariance> covariance;
  if (estimable)
    covariance = {solution.covariance(kY2, kY2), solution.covariance(kZ2, kZ2), solution.covariance(kY2, kZ2)};
  fit.angles.misalignment =
      misalignment_detail::misalignment_figure(solution.parameters[kY2], solution.parameters[kZ2], covariance);
  fit.equation_count = pairs.size();
  fit.degrees_of_freedom = solution.degrees_of_freedom;
  fit.residual_rms = arcsec_figure(solution.residual_rms, std::nullopt);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    fit.residuals.push_back(
        {pairs[i]->alpha_deg, pairs[i]->beta_deg, pairs[i]->rate_dps, solution.residuals[i] / constants::kArcsecond});
  }
  return fit;
}

}  // namespace

void GyroMisalignmentOptions::validate() const {
  if (scale_factor == 0.0 || !std::isfinite(scale_factor)) {
    throw Error(
        fmt::format("gyro misalignment: the scale factor kI must be finite and nonzero, got {}; the angles "
                    "are (V(+) − V(−))/(2·kI·ω)",
                    scale_factor));
  }
  Unit::parse(output_unit);
}

nlohmann::json GyroMisalignmentAngles::to_json() const {
  return {{"delta_theta_y0", delta_theta_y0}, {"delta_theta_x0", delta_theta_x0}, {"delta_theta_y1", delta_theta_y1},
          {"delta_theta_y2", delta_theta_y2}, {"delta_theta_z2", delta_theta_z2}, {"misalignment", misalignment}};
}

GyroMisalignmentResult gyro_misalignment(std::span<const GyroMisalignmentRow> rows,
                                         const GyroMisalignmentOptions& options) {
  options.validate();
  if (rows.empty()) throw Error(SourceLocation{options.source, 0, 0}, "gyro misalignment: no positions given");
  check_positions_in_degrees(rows, options);
  const std::vector<PositionPair> pairs = pair_directions(rows, options);

  std::vector<double> rates;
  for (const PositionPair& p : pairs) rates.push_back(p.rate_dps);
  std::sort(rates.begin(), rates.end());
  rates.erase(std::unique(rates.begin(), rates.end()), rates.end());

  GyroMisalignmentResult result;
  result.output_unit = options.output_unit;
  result.scale_factor = options.scale_factor;
  std::vector<const PositionPair*> all;
  for (const PositionPair& p : pairs) all.push_back(&p);
  for (double rate : rates) {
    std::vector<const PositionPair*> at_rate;
    for (const PositionPair& p : pairs) {
      if (p.rate_dps == rate) at_rate.push_back(&p);
    }
    result.by_rate.push_back(
        {rate, fit_pairs(at_rate, options, fmt::format("gyro misalignment: the positions at {} deg/s", rate))});
  }
  // All rates together: the equations are in angle units, so every rate weighs the same; with the
  // same positions at every rate this is the mean of the per-rate solutions.
  result.combined = fit_pairs(all, options, "gyro misalignment: the positions of all rates");
  std::vector<double> outputs;
  for (const GyroMisalignmentRow& row : rows) outputs.push_back(row.output);
  result.warnings = misalignment_detail::constant_output_warnings(outputs, options.output_unit);
  return result;
}

std::array<double, 5> five_position_misalignment(const FivePositionOutputs& outputs, double scale_factor,
                                                 double rate_dps) {
  if (scale_factor == 0.0 || !std::isfinite(scale_factor)) {
    throw Error(fmt::format("gyro misalignment: the scale factor kI must be finite and nonzero, got {}", scale_factor));
  }
  if (!(rate_dps > 0.0) || !std::isfinite(rate_dps)) {
    throw Error(fmt::format("gyro misalignment: the table rate ω must be positive, got {} deg/s", rate_dps));
  }
  for (std::size_t i = 0; i < 5; ++i) {
    if (!std::isfinite(outputs.plus[i]) || !std::isfinite(outputs.minus[i])) {
      throw Error(fmt::format("gyro misalignment: an output at position {} is not a finite number", i + 1));
    }
  }
  // D_i = V_i(+) − V_i(−); the paper's closed forms (reference README §2).
  std::array<double, 5> d{};
  for (std::size_t i = 0; i < 5; ++i) d[i] = outputs.plus[i] - outputs.minus[i];
  const double denominator = 4.0 * scale_factor * rate_dps;
  return {
      (d[1] - d[0]) / denominator,               // Δθy0
      (2.0 * d[4] - d[1] - d[0]) / denominator,  // Δθx0
      (-d[0] - d[2]) / denominator,              // Δθy1
      (d[2] - d[1]) / denominator,               // Δθy2
      (2.0 * d[3] - d[2] - d[1]) / denominator,  // Δθz2
  };
}

nlohmann::json gyro_fit_json(const GyroMisalignmentFit& fit) {
  nlohmann::json json = fit.angles.to_json();
  json["equation_count"] = fit.equation_count;
  json["degrees_of_freedom"] = fit.degrees_of_freedom;
  json["residual_rms"] = fit.residual_rms;
  nlohmann::json residuals = nlohmann::json::array();
  for (const auto& r : fit.residuals) {
    residuals.push_back({{"alpha_deg", r.alpha_deg},
                         {"beta_deg", r.beta_deg},
                         {"rate_dps", r.rate_dps},
                         {"residual", Figure{r.residual_arcsec, "arcsec", std::nullopt}}});
  }
  json["residuals"] = residuals;
  return json;
}

nlohmann::json by_rate_json(const GyroMisalignmentResult& result) {
  nlohmann::json rates = nlohmann::json::array();
  for (const auto& r : result.by_rate) {
    nlohmann::json entry = gyro_fit_json(r.fit);
    entry["rate_dps"] = r.rate_dps;
    rates.push_back(entry);
  }
  return rates;
}

}  // namespace inertest

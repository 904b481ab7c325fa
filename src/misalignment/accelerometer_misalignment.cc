#include "inertest/misalignment/accelerometer_misalignment.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/io/angle_column.h"
#include "inertest/numerics/compensated_sum.h"
#include "inertest/numerics/statistics.h"
#include "misalignment/misalignment_fit.h"

namespace inertest {
namespace {

using misalignment_detail::arcsec_figure;
using misalignment_detail::cos_deg;
using misalignment_detail::sin_deg;

// Unknowns of one run: the constant c = V0/kI − Δθy0 − Δθy1, then Δθy2, Δθz2.
enum Unknown { kOffset, kY2, kZ2, kUnknownCount };
const std::vector<std::string> kUnknownNames = {"the constant V0/kI - delta_theta_y0 - delta_theta_y1",
                                                "delta_theta_y2", "delta_theta_z2"};

AccelerometerMisalignmentRun fit_run(long run, const std::vector<const AccelerometerMisalignmentRow*>& rows,
                                     const AccelerometerMisalignmentOptions& options) {
  Matrix design(rows.size(), kUnknownCount);
  std::vector<double> observations(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    // Misalignment paper: V/kI = c + Δθz2·sinβ − Δθy2·cosβ.
    design(i, kOffset) = 1.0;
    design(i, kY2) = -cos_deg(rows[i]->beta_deg);
    design(i, kZ2) = sin_deg(rows[i]->beta_deg);
    observations[i] = rows[i]->output / options.scale_factor;
  }
  const LeastSquaresResult solution = misalignment_detail::solve_separating(
      design, observations, kUnknownNames, SourceLocation{options.source, rows.front()->line, 0},
      fmt::format("accelerometer misalignment: the positions of run {}", run),
      "the terms 1, -cos(beta), sin(beta) must be independent over the positions of a run, as with the paper's "
      "beta = 0, 90, 180, 270");
  const bool estimable = solution.degrees_of_freedom > 0;
  auto sigma = [&](Unknown u) { return estimable ? std::optional<double>(solution.standard_error(u)) : std::nullopt; };
  AccelerometerMisalignmentRun result;
  result.run = run;
  result.angles.delta_theta_y2 = arcsec_figure(solution.parameters[kY2], sigma(kY2));
  result.angles.delta_theta_z2 = arcsec_figure(solution.parameters[kZ2], sigma(kZ2));
  std::optional<misalignment_detail::AnglePairCovariance> covariance;
  if (estimable)
    covariance = {solution.covariance(kY2, kY2), solution.covariance(kZ2, kZ2), solution.covariance(kY2, kZ2)};
  result.angles.misalignment =
      misalignment_detail::misalignment_figure(solution.parameters[kY2], solution.parameters[kZ2], covariance);
  result.position_count = rows.size();
  result.degrees_of_freedom = solution.degrees_of_freedom;
  result.residual_rms = {solution.residual_rms * std::abs(options.scale_factor), options.output_unit, std::nullopt};
  return result;
}

// Mean over runs with the standard error of the mean (angles in arcsec on input and output).
AccelerometerMisalignmentAngles combine_runs(const std::vector<AccelerometerMisalignmentRun>& runs) {
  if (runs.size() == 1) return runs.front().angles;
  std::vector<double> y2;
  std::vector<double> z2;
  for (const auto& r : runs) {
    y2.push_back(r.angles.delta_theta_y2.value * constants::kArcsecond);
    z2.push_back(r.angles.delta_theta_z2.value * constants::kArcsecond);
  }
  const double n = static_cast<double>(runs.size());
  const double mean_y2 = mean(y2);
  const double mean_z2 = mean(z2);
  const double sd_y2 = sample_standard_deviation(y2);
  const double sd_z2 = sample_standard_deviation(z2);
  CompensatedSum cross;
  for (std::size_t i = 0; i < runs.size(); ++i) cross.add((y2[i] - mean_y2) * (z2[i] - mean_z2));
  // Covariance of the two means: the sample (co)variances over runs divided by n.
  const misalignment_detail::AnglePairCovariance covariance{sd_y2 * sd_y2 / n, sd_z2 * sd_z2 / n,
                                                            cross.value() / (n - 1.0) / n};
  AccelerometerMisalignmentAngles angles;
  angles.delta_theta_y2 = arcsec_figure(mean_y2, sd_y2 / std::sqrt(n));
  angles.delta_theta_z2 = arcsec_figure(mean_z2, sd_z2 / std::sqrt(n));
  angles.misalignment = misalignment_detail::misalignment_figure(mean_y2, mean_z2, covariance);
  return angles;
}


}  // namespace

void AccelerometerMisalignmentOptions::validate() const {
  if (scale_factor == 0.0 || !std::isfinite(scale_factor)) {
    throw Error(
        fmt::format("accelerometer misalignment: the scale factor kI must be finite and nonzero, got {}; "
                    "the angles are output differences divided by 2·kI",
                    scale_factor));
  }
  Unit::parse(output_unit);
}

nlohmann::json AccelerometerMisalignmentAngles::to_json() const {
  return {{"delta_theta_y2", delta_theta_y2}, {"delta_theta_z2", delta_theta_z2}, {"misalignment", misalignment}};
}

AccelerometerMisalignmentResult accelerometer_misalignment(std::span<const AccelerometerMisalignmentRow> rows,
                                                           const AccelerometerMisalignmentOptions& options) {
  options.validate();
  if (rows.empty()) {
    throw Error(SourceLocation{options.source, 0, 0}, "accelerometer misalignment: no positions given");
  }
  // Positions in radians read as degrees (io/angle_column.h): from a file or arrays.
  std::vector<double> angles;
  for (const AccelerometerMisalignmentRow& row : rows) angles.push_back(row.beta_deg);
  if (const std::optional<std::size_t> i = radians_among_degrees(angles)) {
    throw Error(SourceLocation{options.source, rows[*i].line, 0},
                "accelerometer misalignment: " + radians_message("beta_deg", angles[*i]));
  }
  std::vector<long> run_order;
  std::vector<std::vector<const AccelerometerMisalignmentRow*>> run_rows;
  for (const AccelerometerMisalignmentRow& row : rows) {
    const SourceLocation where{options.source, row.line, 0};
    if (!std::isfinite(row.beta_deg) || !std::isfinite(row.output)) {
      throw Error(where, "accelerometer misalignment: beta_deg and output must be finite numbers");
    }
    const auto found = std::find(run_order.begin(), run_order.end(), row.run);
    const auto index = static_cast<std::size_t>(found - run_order.begin());
    if (found == run_order.end()) {
      run_order.push_back(row.run);
      run_rows.emplace_back();
    }
    for (const auto* other : run_rows[index]) {
      if (other->beta_deg == row.beta_deg) {
        throw Error(where, fmt::format("accelerometer misalignment: beta {} deg appears twice in run {} (first at "
                                       "line {}); give each run its own number in the 'run' column",
                                       row.beta_deg, row.run, other->line));
      }
    }
    run_rows[index].push_back(&row);
  }
  AccelerometerMisalignmentResult result;
  result.output_unit = options.output_unit;
  result.scale_factor = options.scale_factor;
  for (std::size_t i = 0; i < run_order.size(); ++i)
    result.by_run.push_back(fit_run(run_order[i], run_rows[i], options));
  result.combined = combine_runs(result.by_run);
  std::vector<double> outputs;
  for (const AccelerometerMisalignmentRow& row : rows) outputs.push_back(row.output);
  result.warnings = misalignment_detail::constant_output_warnings(outputs, options.output_unit);
  // The combined angles' 1-sigma: one run's from its fit's residuals, several runs' from their scatter
  // (3 runs: 2 degrees of freedom, 58 % coverage measured over 200 trials).
  const std::size_t degrees_of_freedom =
      result.by_run.size() == 1 ? result.by_run.front().degrees_of_freedom : result.by_run.size() - 1;
  if (const std::optional<std::string> few = few_degrees_of_freedom_warning(
          result.by_run.size() == 1 ? "the run's fit" : "the mean over runs", degrees_of_freedom, "tests")) {
    result.warnings.push_back(*few);
  }
  return result;
}

std::array<double, 2> four_position_misalignment(double v_0, double v_90, double v_180, double v_270,
                                                 double scale_factor) {
  if (scale_factor == 0.0 || !std::isfinite(scale_factor)) {
    throw Error(fmt::format("accelerometer misalignment: the scale factor kI must be finite and nonzero, got {}",
                            scale_factor));
  }
  const std::array<double, 4> outputs = {v_0, v_90, v_180, v_270};
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    if (!std::isfinite(outputs[i])) {  // a NaN gave a NaN angle, silently
      throw Error(fmt::format("accelerometer misalignment: the output at {} deg is not a finite number", 90 * i));
    }
  }
  // The misalignment paper (reference README §2): Δθy2 = (V(π) − V(0))/(2kI), Δθz2 = (V(π/2) − V(3π/2))/(2kI).
  return {(v_180 - v_0) / (2.0 * scale_factor), (v_90 - v_270) / (2.0 * scale_factor)};
}

nlohmann::json by_run_json(const AccelerometerMisalignmentResult& result) {
  nlohmann::json runs = nlohmann::json::array();
  for (const auto& r : result.by_run) {
    nlohmann::json entry = r.angles.to_json();
    entry["run"] = r.run;
    entry["position_count"] = r.position_count;
    entry["degrees_of_freedom"] = r.degrees_of_freedom;
    entry["residual_rms"] = r.residual_rms;
    runs.push_back(entry);
  }
  return runs;
}

}  // namespace inertest

#include "inertest/centrifuge/drift_calibration.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace inertest::centrifuge {
namespace {

constexpr double kBetaTolerance = 1e-9;  // rad: equal platform angles, read from text in degrees
constexpr double kDegPerHourPerRadPerSecond = 3600.0 / constants::kDegree;

// The centrifuge errors of eq. (5) that can be measured or estimated, in a fixed order.
enum ErrorIndex : std::size_t { kErrorK1, kErrorK2, kErrorDeltaOmega, kErrorCount };
constexpr std::array<const char*, kErrorCount> kErrorNames = {"k1", "k2", "delta_omega"};
constexpr std::array<const char*, kErrorCount> kErrorUnits = {"rad", "rad", "rad/s"};
constexpr std::array<const char*, kErrorCount> kPerErrorUnit = {"/rad", "/rad", "/(rad/s)"};

std::array<std::optional<double>, kErrorCount> given_errors(const DriftCalibrationOptions& options) {
  return {options.k1_rad, options.k2_rad, options.delta_omega_rad_s};
}

const std::vector<double>& error_column(const CentrifugeDesign& design, std::size_t error) {
  if (error == kErrorK1) return design.per_k1;
  if (error == kErrorK2) return design.per_k2;
  return design.per_delta_omega;
}

double normalised_beta(double beta) {
  const double turn = 2.0 * constants::kPi;
  double b = std::fmod(beta, turn);
  if (b < 0.0) b += turn;
  if (turn - b <= kBetaTolerance) b = 0.0;
  return b;
}

std::string g_label(double accel_g) { return fmt::format("{:g} g", accel_g); }
std::string beta_label(double beta) { return fmt::format("{:g} deg", beta / constants::kDegree); }

// Checks every run and that no (g-level, beta) is run twice; returns the number of g-levels. The
// g-levels need not hold the same platform angles (the paper's eqs. 12, 15-16 stack the same betas,
// but any runs whose design has full rank identify the coefficients): require_identifiable judges.
std::size_t check_runs(std::span<const CentrifugeRun> runs) {
  if (runs.empty()) throw Error("centrifuge: no runs");
  struct Level {
    double accel_g;
    std::vector<const CentrifugeRun*> runs;
  };
  std::vector<Level> levels;
  for (const CentrifugeRun& run : runs) {
    if (!(std::isfinite(run.accel_g) && run.accel_g > 0.0)) {
      throw Error(run.location, fmt::format("centrifuge: accel_g must be positive, got {}", run.accel_g));
    }
    if (run.omega_rad_s && !(std::isfinite(*run.omega_rad_s) && *run.omega_rad_s > 0.0)) {
      throw Error(run.location, fmt::format("centrifuge: omega_rad_s must be positive, got {}", *run.omega_rad_s));
    }
    if (!std::isfinite(run.beta_rad)) throw Error(run.location, "centrifuge: beta is not finite");
    for (double a : run.amplitudes) {
      if (!std::isfinite(a)) throw Error(run.location, "centrifuge: a harmonic amplitude is not finite");
    }
    auto level = std::find_if(levels.begin(), levels.end(), [&](const Level& l) { return l.accel_g == run.accel_g; });
    if (level == levels.end()) {
      levels.push_back({run.accel_g, {}});
      level = std::prev(levels.end());
    }
    for (const CentrifugeRun* other : level->runs) {
      if (std::abs(normalised_beta(other->beta_rad) - normalised_beta(run.beta_rad)) <= kBetaTolerance) {
        throw Error(run.location, fmt::format("centrifuge: a second run at {} and beta = {} (the first is at {})",
                                              g_label(run.accel_g), beta_label(run.beta_rad),
                                              other->location.to_string()));
      }
    }
    level->runs.push_back(&run);
  }
  return levels.size();
}

// A run that gives its main-axis rate Omega as well as its g-level A: with the radius and the site's
// gravity they must agree, A = Omega^2 R0 / g (paper section 6), or one of them is wrong (a radius of
// another arm, a rate in deg/s) and the coefficients with it. The g-level is the run's set point, so
// Omega was set from it; the tolerance, 1 %, passes a level computed with standard gravity instead of
// the site's (at most 0.3 % apart on the Earth's surface) and rounded to three significant figures
// (at most 0.5 %), and catches every such mistake of more than 1 %.
constexpr double kGLevelTolerance = 1e-2;

void check_g_levels(std::span<const CentrifugeRun> runs, const CentrifugeSite& site) {
  for (const CentrifugeRun& run : runs) {
    if (!run.omega_rad_s) continue;
    const double level = *run.omega_rad_s * *run.omega_rad_s * site.radius_m / site.gravity_m_s2;
    if (std::abs(level - run.accel_g) > kGLevelTolerance * run.accel_g) {
      throw Error(run.location,
                  fmt::format("centrifuge: omega_rad_s {:.10g} at radius {} m and gravity {} m/s^2 is a g-level of "
                              "{:.6g} g (Omega^2 R0 / g), not the run's accel_g {:g}: they differ by {:.3g} %, more "
                              "than {:g} % (is --radius or --gravity wrong, or omega_rad_s in another unit?)",
                              *run.omega_rad_s, site.radius_m, site.gravity_m_s2, level, run.accel_g,
                              100.0 * std::abs(level - run.accel_g) / run.accel_g, 100.0 * kGLevelTolerance));
    }
  }
}

double run_omega(const CentrifugeRun& run, const CentrifugeSite& site) {
  // Paper section 6: the main axis turns at Omega = sqrt(A g / R0) for a g-level A.
  return run.omega_rad_s ? *run.omega_rad_s : std::sqrt(run.accel_g * site.gravity_m_s2 / site.radius_m);
}

// Names the parameters that lie in the (numerical) null space of the column-normalised design:
// only combinations of them are determined. Throws Error when there are any.
void require_identifiable(const Matrix& design, const std::vector<std::string>& names, double threshold,
                          std::size_t g_levels) {
  const auto rows = static_cast<Eigen::Index>(design.rows);
  const auto cols = static_cast<Eigen::Index>(design.cols);
  if (design.rows < design.cols) {
    throw Error(fmt::format("centrifuge: {} harmonic amplitudes cannot determine {} parameters", design.rows,
                            design.cols));
  }
  Eigen::MatrixXd a(rows, cols);
  for (Eigen::Index r = 0; r < rows; ++r) {
    for (Eigen::Index c = 0; c < cols; ++c) a(r, c) = design(static_cast<std::size_t>(r), static_cast<std::size_t>(c));
  }
  for (Eigen::Index c = 0; c < cols; ++c) {
    const double norm = a.col(c).norm();
    if (norm > 0.0) a.col(c) /= norm;
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  Eigen::Index rank = 0;
  while (rank < cols && s(rank) > threshold * s(0)) ++rank;
  if (rank == cols) return;
  // A parameter is identifiable exactly when its row of the null-space basis is zero.
  const Eigen::MatrixXd null_space = svd.matrixV().rightCols(cols - rank);
  std::string unidentifiable;
  for (Eigen::Index j = 0; j < cols; ++j) {
    if (null_space.row(j).norm() > 1e-2) {
      unidentifiable += (unidentifiable.empty() ? "" : ", ") + names[static_cast<std::size_t>(j)];
    }
  }
  std::string hint = g_levels < 2 ? "; a single g-level cannot separate them: add a second g-level (paper eqs. 15-16)"
                                   : "; add g-levels or platform angles";
  throw Error(fmt::format("centrifuge: the test cannot identify {} (rank {} of {}: only combinations of them are "
                          "determined, singular values below {:g} of the largest){}",
                          unidentifiable, rank, cols, threshold, hint));
}

std::optional<double> uncertainty_of(const LeastSquaresResult& fit, std::size_t i) {
  if (fit.degrees_of_freedom == 0) return std::nullopt;
  return fit.standard_error(i);
}

std::array<Figure, kDriftTermCount> coefficient_figures(std::span<const double> values, const std::string& unit_suffix) {
  std::array<Figure, kDriftTermCount> figures;
  for (std::size_t j = 0; j < kDriftTermCount; ++j) {
    figures[j] = {values[j], std::string(drift_term_unit(j)) + unit_suffix, std::nullopt};
  }
  return figures;
}

nlohmann::json amplitude_json(const HarmonicAmplitudes& amplitudes) {
  nlohmann::json json = nlohmann::json::object();
  for (std::size_t h = 0; h < kHarmonicCount; ++h) {
    json[std::string(harmonic_name(h))] = Figure{amplitudes[h], "deg/h", std::nullopt};
  }
  return json;
}

}  // namespace

nlohmann::json coefficient_json(const std::array<Figure, kDriftTermCount>& figures) {
  nlohmann::json json = nlohmann::json::object();
  for (std::size_t j = 0; j < kDriftTermCount; ++j) json[std::string(drift_term_name(j))] = figures[j];
  return json;
}

std::vector<CentrifugeRun> analyse_sample_runs(std::span<const CentrifugeSampleRun> runs) {
  std::vector<CentrifugeRun> analysed;
  analysed.reserve(runs.size());
  for (const CentrifugeSampleRun& run : runs) {
    HarmonicFit fit;
    try {
      fit = analyse_harmonics(run.gamma_rad, run.output);
    } catch (const Error& e) {
      throw Error(run.location, fmt::format("run at {} and beta = {}: {}", g_label(run.accel_g),
                                            beta_label(run.beta_rad), e.message()));
    }
    analysed.push_back({run.accel_g, run.omega_rad_s, run.beta_rad, fit.amplitudes, fit, run.location});
  }
  return analysed;
}

// Over 0.1 rad (5.7 deg) or 0.1 rad/s no centrifuge's error is small, as eq. (5)'s first order takes it.
constexpr double kLargestError = 0.1;

void DriftCalibrationOptions::validate() const {
  site.validate();
  const auto errors = given_errors(*this);
  for (std::size_t e = 0; e < kErrorCount; ++e) {
    if (errors[e] && !std::isfinite(*errors[e])) throw Error(fmt::format("centrifuge: {} is not finite", kErrorNames[e]));
    // The errors are small angles (rad) and a small rate difference (rad/s): 20 for 2e-5 is one in
    // arcsec or in another unit, and gave D_I = 3.1e6 silently.
    if (errors[e] && std::abs(*errors[e]) > kLargestError) {
      throw Error(fmt::format("centrifuge: {} = {} {} is not a small error (over {}): the errors are in rad and rad/s",
                              kErrorNames[e], *errors[e], kErrorUnits[e], kLargestError));
    }
  }
  if (estimate_errors && !compensation) {
    throw Error("centrifuge: estimating the centrifuge errors needs compensation (it is off)");
  }
  if (!(rank_threshold > 0.0 && rank_threshold < 1.0)) {
    throw Error(fmt::format("centrifuge: rank threshold must lie in (0, 1), got {}", rank_threshold));
  }
}

std::vector<double> CentrifugeDesign::compensation(const CentrifugeErrors& errors) const {
  std::vector<double> epsilon(observations.size());
  for (std::size_t r = 0; r < epsilon.size(); ++r) {
    epsilon[r] = earth_rate[r] + errors.k1_rad * per_k1[r] + errors.k2_rad * per_k2[r] +
                 errors.delta_omega_rad_s * per_delta_omega[r];
  }
  return epsilon;
}

CentrifugeDesign centrifuge_design(std::span<const CentrifugeRun> runs, const CentrifugeSite& site) {
  CentrifugeDesign design;
  const std::size_t m = runs.size() * kHarmonicCount;
  design.structure = Matrix(m, kDriftTermCount);
  design.observations.reserve(m);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const HarmonicModel model = centrifuge_harmonic_model(site, run_omega(runs[i], site), runs[i].beta_rad);
    for (std::size_t h = 0; h < kHarmonicCount; ++h) {
      const std::size_t row = i * kHarmonicCount + h;  // eq. (12): k0, k1c, k1s, k2c, k2s per beta
      for (std::size_t j = 0; j < kDriftTermCount; ++j) design.structure(row, j) = model.structure[h][j];
      design.observations.push_back(runs[i].amplitudes[h]);
      design.earth_rate.push_back(model.earth_rate[h]);
      design.per_k1.push_back(model.per_k1[h]);
      design.per_k2.push_back(model.per_k2[h]);
      design.per_delta_omega.push_back(model.per_delta_omega[h]);
    }
  }
  return design;
}

DriftCalibrationResult calibrate_drift_coefficients(std::span<const CentrifugeRun> runs,
                                                    const DriftCalibrationOptions& options) {
  options.validate();
  DriftCalibrationResult result;
  result.g_levels = check_runs(runs);
  check_g_levels(runs, options.site);
  for (const CentrifugeRun& run : runs) {
    // Eq. (11)'s amplitudes are the output's harmonics over whole revolutions (the paper's test
    // samples the output over them): less than one is a fit the revolution does not support.
    // Under a tenth of a turn is no harmonic fit: angles in radians (a turn is 6.28 "deg") gave
    // coefficients a million times off with this warning alone.
    if (run.harmonic_fit && run.harmonic_fit->part_of_a_revolution && run.harmonic_fit->revolutions < 0.1) {
      throw Error(fmt::format("run at {} and beta = {}: the samples cover {:.3g} of a revolution ({:.3g} deg of "
                              "gamma): eq. (11)'s harmonics need the turn; are the angles in radians? gamma_deg is in "
                              "degrees",
                              g_label(run.accel_g), beta_label(run.beta_rad), run.harmonic_fit->revolutions,
                              360.0 * run.harmonic_fit->revolutions));
    }
    if (run.harmonic_fit && run.harmonic_fit->part_of_a_revolution) {
      result.warnings.push_back(fmt::format(
          "run at {} and beta = {}: the samples cover {:.3g} of a revolution: its harmonics are fitted over less "
          "than one turn and may mix with drift",
          g_label(run.accel_g), beta_label(run.beta_rad), run.harmonic_fit->revolutions));
    }
    if (run.harmonic_fit && run.harmonic_fit->constant_output) {
      result.warnings.push_back(fmt::format(
          "run at {} and beta = {}: all {} samples equal {:.10g} deg/h (a stuck channel?); its harmonics of 0 are "
          "not a measurement",
          g_label(run.accel_g), beta_label(run.beta_rad), run.harmonic_fit->sample_count, run.amplitudes[kK0]));
    }
  }
  result.site = options.site;
  result.compensation = options.compensation;
  const CentrifugeDesign design = centrifuge_design(runs, options.site);
  const std::size_t m = design.observations.size();

  // Which errors are measured, estimated, or taken as zero.
  const auto given = given_errors(options);
  std::vector<std::size_t> estimated;
  std::array<double, kErrorCount> values{};
  std::array<std::optional<double>, kErrorCount> uncertainties{};
  for (std::size_t e = 0; e < kErrorCount; ++e) {
    if (given[e]) {
      result.measured_errors.emplace_back(kErrorNames[e]);
      values[e] = *given[e];
    } else if (options.estimate_errors) {
      estimated.push_back(e);
    } else if (options.compensation) {
      result.warnings.push_back(fmt::format("{} not measured: taken as 0 in the compensation (estimate_errors "
                                            "estimates it from two or more g-levels)",
                                            kErrorNames[e]));
    }
  }
  if (options.estimate_errors && estimated.empty()) {
    result.warnings.push_back("estimate_errors: every centrifuge error was measured; nothing to estimate");
  }

  // Eq. (14), extended by the estimated errors' columns: Y - epsilon_known = [Phi E] [q; e].
  const std::size_t n = kDriftTermCount + estimated.size();
  Matrix augmented(m, n);
  std::vector<std::string> names;
  for (std::size_t j = 0; j < kDriftTermCount; ++j) names.emplace_back(drift_term_name(j));
  for (std::size_t e : estimated) names.emplace_back(kErrorNames[e]);
  for (std::size_t r = 0; r < m; ++r) {
    for (std::size_t j = 0; j < kDriftTermCount; ++j) augmented(r, j) = design.structure(r, j);
    for (std::size_t k = 0; k < estimated.size(); ++k) {
      augmented(r, kDriftTermCount + k) = error_column(design, estimated[k])[r];
    }
  }
  require_identifiable(augmented, names, options.rank_threshold, result.g_levels);

  const CentrifugeErrors known{values[kErrorK1], values[kErrorK2], values[kErrorDeltaOmega]};
  std::vector<double> corrected = design.observations;
  if (options.compensation) {
    const std::vector<double> epsilon = design.compensation(known);
    for (std::size_t r = 0; r < m; ++r) corrected[r] -= epsilon[r];
  }
  LeastSquaresOptions solve_options;
  solve_options.parameter_names = names;
  // Eq. (14) unweighted, as the paper solves it; its covariance from each amplitude's own variance:
  // over whole turns a mean k0 of N samples has σ²/N, a cosine or sine amplitude 2σ²/N (eq. 11's
  // DFT bins doubled). One variance for all overstated D_F's 1-sigma by 36 % (81 % coverage) and
  // understated the cross terms' (63-66 %).
  for (std::size_t r = 0; r < m; ++r) {
    const CentrifugeRun& run = runs[r / kHarmonicCount];
    const double samples = run.harmonic_fit ? static_cast<double>(run.harmonic_fit->sample_count) : 1.0;
    solve_options.relative_variances.push_back((r % kHarmonicCount == kK0 ? 1.0 : 2.0) / samples);
  }
  const LeastSquaresResult fit = solve_least_squares(augmented, corrected, solve_options);
  if (fit.degrees_of_freedom == 0) {
    result.warnings.push_back("as many amplitudes as parameters: no redundancy, uncertainties unknown");
  }

  for (std::size_t j = 0; j < kDriftTermCount; ++j) {
    result.coefficients[j] = {fit.parameters[j], std::string(drift_term_unit(j)), uncertainty_of(fit, j)};
  }
  result.residual_rms = {fit.residual_rms, "deg/h", std::nullopt};
  result.degrees_of_freedom = fit.degrees_of_freedom;
  for (std::size_t k = 0; k < estimated.size(); ++k) {
    const std::size_t e = estimated[k];
    const std::size_t i = kDriftTermCount + k;
    values[e] = fit.parameters[i];
    uncertainties[e] = uncertainty_of(fit, i);
    EstimatedCentrifugeError estimate{kErrorNames[e], {fit.parameters[i], kErrorUnits[e], uncertainty_of(fit, i)}, {}};
    if (fit.degrees_of_freedom > 0) {
      for (std::size_t other = 0; other < n; ++other) {
        if (other == i) continue;
        const double denominator = std::sqrt(fit.covariance(i, i) * fit.covariance(other, other));
        estimate.correlation.emplace_back(names[other], denominator > 0.0 ? fit.covariance(i, other) / denominator : 0.0);
      }
    }
    result.estimated_errors.push_back(std::move(estimate));
  }
  result.errors = options.compensation ? CentrifugeErrors{values[kErrorK1], values[kErrorK2], values[kErrorDeltaOmega]}
                                       : CentrifugeErrors{};

  // Paper section 6: each error alone through (Phi^T Phi)^-1 Phi^T epsilon_i.
  LeastSquaresOptions influence_options;
  influence_options.parameter_names.assign(names.begin(), names.begin() + kDriftTermCount);
  for (std::size_t e = 0; e < kErrorCount; ++e) {
    const LeastSquaresResult per_unit = solve_least_squares(design.structure, error_column(design, e), influence_options);
    std::vector<double> shift(kDriftTermCount);
    for (std::size_t j = 0; j < kDriftTermCount; ++j) shift[j] = per_unit.parameters[j] * values[e];
    ErrorInfluence influence;
    influence.error = kErrorNames[e];
    influence.magnitude = Figure{values[e], kErrorUnits[e], uncertainties[e]};
    influence.shift = coefficient_figures(shift, "");
    influence.sensitivity = coefficient_figures(per_unit.parameters, kPerErrorUnit[e]);
    result.influence.push_back(std::move(influence));
  }
  const LeastSquaresResult earth = solve_least_squares(design.structure, design.earth_rate, influence_options);
  ErrorInfluence earth_influence;
  earth_influence.error = "earth_rate";
  earth_influence.magnitude = Figure{options.site.earth_rate_rad_s * kDegPerHourPerRadPerSecond, "deg/h", std::nullopt};
  earth_influence.shift = coefficient_figures(earth.parameters, "");
  result.influence.push_back(std::move(earth_influence));

  for (std::size_t i = 0; i < runs.size(); ++i) {
    RunResidual run{runs[i].accel_g, run_omega(runs[i], options.site), runs[i].beta_rad, runs[i].amplitudes, {},
                    runs[i].harmonic_fit};
    for (std::size_t h = 0; h < kHarmonicCount; ++h) run.residuals[h] = fit.residuals[i * kHarmonicCount + h];
    result.runs.push_back(run);
  }
  return result;
}

nlohmann::json centrifuge_errors_json(const DriftCalibrationResult& result) {
  nlohmann::json errors_json = nlohmann::json::object();
  const CentrifugeErrors& errors = result.errors;
  const std::array<double, kErrorCount> used = {errors.k1_rad, errors.k2_rad, errors.delta_omega_rad_s};
  for (std::size_t e = 0; e < kErrorCount; ++e) {
    const auto& measured_errors = result.measured_errors;
    const bool measured = std::find(measured_errors.begin(), measured_errors.end(), kErrorNames[e]) != measured_errors.end();
    const auto estimate = std::find_if(result.estimated_errors.begin(), result.estimated_errors.end(),
                                       [&](const EstimatedCentrifugeError& x) { return x.name == kErrorNames[e]; });
    nlohmann::json entry;
    if (estimate != result.estimated_errors.end()) {
      nlohmann::json correlation = nlohmann::json::object();
      for (const auto& [name, rho] : estimate->correlation) correlation[name] = rho;
      entry = {{"value", estimate->value}, {"source", "estimated"}, {"correlation", correlation}};
    } else if (measured && !result.compensation) {
      // Measured for the influence analysis (paper section 6) but applied nowhere: the value given,
      // said so (it read "measured" with the 0 that was applied).
      entry = {{"value", result.influence.at(e).magnitude}, {"source", "measured, not applied (compensation off)"}};
    } else {
      entry = {{"value", Figure{used[e], kErrorUnits[e], std::nullopt}},
               {"source", measured ? "measured" : "not measured (0)"}};
    }
    errors_json[kErrorNames[e]] = entry;
  }
  return errors_json;
}

nlohmann::json influence_json(const DriftCalibrationResult& result) {
  nlohmann::json influence = nlohmann::json::object();
  for (const ErrorInfluence& i : result.influence) {
    nlohmann::json entry = {{"magnitude", i.magnitude}, {"shift", coefficient_json(i.shift)}};
    if (i.sensitivity) entry["sensitivity"] = coefficient_json(*i.sensitivity);
    influence[i.error] = entry;
  }
  return influence;
}

nlohmann::json runs_json(const DriftCalibrationResult& result) {
  nlohmann::json runs = nlohmann::json::array();
  for (const RunResidual& run : result.runs) {
    nlohmann::json entry = {{"accel_g", run.accel_g},
                            {"omega", Figure{run.omega_rad_s, "rad/s", std::nullopt}},
                            {"beta", Figure{run.beta_rad / constants::kDegree, "deg", std::nullopt}},
                            {"amplitudes", amplitude_json(run.amplitudes)},
                            {"residuals", amplitude_json(run.residuals)}};
    if (run.harmonic_fit) {
      entry["harmonic_fit"] = {{"method", to_string(run.harmonic_fit->method)},
                               {"samples", run.harmonic_fit->sample_count},
                               {"revolutions", run.harmonic_fit->revolutions},
                               {"residual_rms", Figure{run.harmonic_fit->residual_rms, "deg/h", std::nullopt}}};
    }
    runs.push_back(entry);
  }
  return runs;
}

nlohmann::json site_json(const CentrifugeSite& site) {
  return {{"radius", Figure{site.radius_m, "m", std::nullopt}},
          {"latitude", Figure{site.latitude_rad / constants::kDegree, "deg", std::nullopt}},
          {"gravity", Figure{site.gravity_m_s2, "m/s^2", std::nullopt}},
          {"earth_rate", Figure{site.earth_rate_rad_s * kDegPerHourPerRadPerSecond, "deg/h", std::nullopt}}};
}

}  // namespace inertest::centrifuge

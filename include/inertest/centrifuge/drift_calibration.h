// Calibration of a gyro's ten acceleration-sensitive drift coefficients on a precision centrifuge
// with a counter-rotating platform, with the centrifuge's errors compensated (the
// centrifuge paper, core/citations.h, sections 5-6):
//   harmonic amplitudes of each run (eq. 11) stacked into Y (eqs. 12, 15), the structure matrix
//   Phi built from the first-order model (centrifuge_model.h; eqs. 13, 16), the compensation
//   vector epsilon (Earth rate and centrifuge errors), and least squares
//   q = (Phi^T Phi)^-1 Phi^T (Y - epsilon) (eq. 14) with the covariance of q.
// Error influence (paper section 6): the shift (Phi^T Phi)^-1 Phi^T epsilon_i of every coefficient
// caused by each error alone. Beyond the paper: with two or more g-levels, the unmeasured
// centrifuge errors k1, k2, delta-omega can be estimated together with the coefficients.
//
// Units: see centrifuge_model.h. Coefficients are reported in deg/h, deg/h/g, deg/h/g^2 with g the
// standard gravity 9.80665 m/s^2 (what Unit::parse reads as g), converted from the site's gravity
// of the paper's A = Omega^2 R0 / g: per site g they would be (g_site / 9.80665)^n times these.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "inertest/centrifuge/centrifuge_model.h"
#include "inertest/centrifuge/harmonic_analysis.h"
#include "inertest/core/error.h"
#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/numerics/least_squares.h"

namespace inertest::centrifuge {

// One run: one g-level and one platform angle beta, with the five harmonic amplitudes of the
// output over whole platform revolutions.
struct CentrifugeRun {
  double accel_g = 0.0;               // nominal g-level; runs with equal accel_g form one g-level
  std::optional<double> omega_rad_s;  // main-axis rate Omega; absent: sqrt(accel_g * g / R0)
  double beta_rad = 0.0;              // platform angle about axis C
  HarmonicAmplitudes amplitudes{};    // k0, k1c, k1s, k2c, k2s (deg/h)
  std::optional<HarmonicFit> harmonic_fit;  // present when the amplitudes come from raw samples
  SourceLocation location;            // where the run is in its input, for messages
};

// One run as raw samples of the gyro output (deg/h) at angles gamma over platform revolutions.
struct CentrifugeSampleRun {
  double accel_g = 0.0;
  std::optional<double> omega_rad_s;
  double beta_rad = 0.0;
  std::vector<double> gamma_rad;
  std::vector<double> output;  // deg/h
  SourceLocation location;
};

// Harmonic analysis (eq. 11) of every sample run; an error names the run's location.
std::vector<CentrifugeRun> analyse_sample_runs(std::span<const CentrifugeSampleRun> runs);

struct DriftCalibrationOptions {
  CentrifugeSite site;
  // The measured centrifuge errors; absent means "not measured" (taken as 0, or estimated when
  // estimate_errors is set).
  std::optional<double> k1_rad;
  std::optional<double> k2_rad;
  std::optional<double> delta_omega_rad_s;
  // false sets epsilon = 0, as the paper's uncompensated comparison does.
  bool compensation = true;
  // Estimate the unmeasured errors together with the coefficients (needs two or more g-levels).
  bool estimate_errors = false;
  // A design whose column-normalised singular values fall below this fraction of the largest
  // cannot identify the parameters of the corresponding directions. One g-level leaves D_F, D_II,
  // D_OO, D_SS tied together up to the Coriolis term (relative singular value ~1e-5); two g-levels
  // even 1 % apart stay above 1e-3.
  double rank_threshold = 1e-4;

  // Throws Error for an invalid site, non-finite errors, or estimate_errors without compensation.
  void validate() const;
};

// The stacked design of eqs. (13), (15)-(16): five rows per run in run order (k0, k1c, k1s, k2c,
// k2s), with epsilon split by source.
struct CentrifugeDesign {
  Matrix structure;                     // Phi, 10 columns in the order of q
  std::vector<double> observations;     // Y (deg/h)
  std::vector<double> earth_rate;       // epsilon from the Earth rate (deg/h)
  std::vector<double> per_k1;           // epsilon per rad of k1
  std::vector<double> per_k2;           // epsilon per rad of k2
  std::vector<double> per_delta_omega;  // epsilon per rad/s of delta-omega

  // epsilon = earth_rate + k1 per_k1 + k2 per_k2 + dOmega per_delta_omega.
  std::vector<double> compensation(const CentrifugeErrors& errors) const;
};

// Builds Phi, Y and the parts of epsilon for any runs (any betas, any number of g-levels).
CentrifugeDesign centrifuge_design(std::span<const CentrifugeRun> runs, const CentrifugeSite& site);

// The shift of every coefficient caused by one error alone: (Phi^T Phi)^-1 Phi^T epsilon_i, i.e.
// the uncompensated estimate minus the compensated one.
struct ErrorInfluence {
  std::string error;   // "k1", "k2", "delta_omega", "earth_rate"
  Figure magnitude;    // the error's value (rad, rad/s; the Earth rate in deg/h)
  std::array<Figure, kDriftTermCount> shift;
  // Shift per unit of the error (coefficient unit per rad or per rad/s); absent for the Earth rate.
  std::optional<std::array<Figure, kDriftTermCount>> sensitivity;
};

// A centrifuge error estimated with the coefficients.
struct EstimatedCentrifugeError {
  std::string name;  // "k1", "k2", "delta_omega"
  Figure value;      // with its 1-sigma uncertainty
  // Correlation coefficient with every other estimated parameter (coefficients and errors).
  std::vector<std::pair<std::string, double>> correlation;
};

struct RunResidual {
  double accel_g = 0.0;
  double omega_rad_s = 0.0;
  double beta_rad = 0.0;
  HarmonicAmplitudes amplitudes{};
  HarmonicAmplitudes residuals{};  // Y - epsilon - Phi q, per amplitude (deg/h)
  std::optional<HarmonicFit> harmonic_fit;
};

struct DriftCalibrationResult {
  std::array<Figure, kDriftTermCount> coefficients;  // D_F ... D_OS with 1-sigma uncertainties
  Figure residual_rms;                // rms of Y - epsilon - Phi q over all amplitudes (deg/h)
  std::size_t degrees_of_freedom = 0;
  std::size_t g_levels = 0;
  CentrifugeSite site;
  bool compensation = true;
  CentrifugeErrors errors;            // the values in epsilon (measured, estimated, or 0)
  std::vector<std::string> measured_errors;   // names of the errors given as measured
  std::vector<EstimatedCentrifugeError> estimated_errors;
  std::vector<ErrorInfluence> influence;
  std::vector<RunResidual> runs;
  std::vector<std::string> warnings;
};

// The JSON of the result's parts, for its spec (src/procedures/centrifuge_spec.cc): the coefficients
// by name (D_F ... D_OS), the errors in epsilon with their source ("measured", "estimated" with the
// correlations, "not measured (0)"), the influence of each error alone (magnitude, shift of every
// coefficient and, when known, that shift per unit error), the residuals of each run, and the site.
nlohmann::json coefficient_json(const std::array<Figure, kDriftTermCount>& figures);
nlohmann::json centrifuge_errors_json(const DriftCalibrationResult& result);
nlohmann::json influence_json(const DriftCalibrationResult& result);
nlohmann::json runs_json(const DriftCalibrationResult& result);
nlohmann::json site_json(const CentrifugeSite& site);

// Throws Error (at the offending run's location where known) for an invalid run, a run whose
// omega_rad_s, with the site's radius and gravity, gives a g-level more than 1 % from its accel_g
// (Omega^2 R0 / g), a duplicated (g-level, beta) run, fewer amplitudes than parameters, or a design that cannot identify some
// parameters (naming them). The g-levels may hold different platform angles when the design still
// has full rank.
DriftCalibrationResult calibrate_drift_coefficients(std::span<const CentrifugeRun> runs,
                                                    const DriftCalibrationOptions& options);

}  // namespace inertest::centrifuge

namespace inertest {

// The procedure's one description (src/procedures/centrifuge_spec.cc): FILE (harmonic amplitudes or
// raw samples) and the site, the measured errors and the compensation as parameters.
ProcedureSpec centrifuge_spec();

}  // namespace inertest

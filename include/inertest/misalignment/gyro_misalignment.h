// Misalignment separation of a gyro on a single-axis rate table (the misalignment
// paper: Li Wei, Ren Shunqing, Zhao Hongbo, "misalignment angle separation of inertial instruments",
// HIT; core/citations.h).
//
// Error angles (rad inside the library, reported in arcsec): table face to table axis Δθy0, Δθx0;
// fixture face Δθy1; gyro input axis to its mounting face Δθy2, Δθz2. The fixture is turned β about
// the table face normal, the gyro α about its mounting normal, and the table turns at +ω and -ω.
// Input rate, paper eq. for ωI:
//   ωI = ωe·cosφ·sin(ωt)·cosβ − Δθy0·ω·cosβ + ωe·cosφ·cos(ωt)·sinβ + Δθx0·ω·sinβ
//        − Δθy1·ω + Δθz2·ω·sinα − Δθy2·ω·cosα
// Averaged over whole revolutions the Earth-rate terms vanish; with V = V0 + kI·ωI the difference of
// the two directions at one position is (derived from ωI, V0 cancels):
//   V(+) − V(−) = 2·kI·ω·(−Δθy0·cosβ + Δθx0·sinβ − Δθy1 + Δθz2·sinα − Δθy2·cosα)       (*)
// The paper uses five positions and closed forms (five_position_misalignment below). Beyond the
// paper, gyro_misalignment() solves (*) by least squares for any set of positions that identifies
// the five angles, at every rate and over all rates together.
//
// Units of this header: position angles in deg, table rates in deg/s, kI in output units per deg/s.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"

namespace inertest {

// One position and direction: the output averaged over whole revolutions.
struct GyroMisalignmentRow {
  double alpha_deg = 0.0;  // gyro turned about its mounting normal
  double beta_deg = 0.0;   // fixture turned about the table face normal
  double rate_dps = 0.0;   // table rate; its sign is the direction
  double output = 0.0;     // mean output over whole revolutions, output units
  std::size_t line = 0;    // 1-based line in GyroMisalignmentOptions::source, 0 if none
};

struct GyroMisalignmentOptions {
  double scale_factor = 0.0;      // kI, output units per deg/s; must be finite and nonzero
  std::string output_unit = "1";  // for the report only
  std::string source;             // file the rows came from, for error locations

  // Throws Error for a zero or non-finite scale factor or an unknown output unit.
  void validate() const;
};

// The five angles and the misalignment γ = √(Δθy2² + Δθz2²), all in arcsec.
struct GyroMisalignmentAngles {
  Figure delta_theta_y0;
  Figure delta_theta_x0;
  Figure delta_theta_y1;
  Figure delta_theta_y2;
  Figure delta_theta_z2;
  Figure misalignment;

  nlohmann::json to_json() const;
};

struct GyroMisalignmentResidual {
  double alpha_deg = 0.0;
  double beta_deg = 0.0;
  double rate_dps = 0.0;         // |ω|
  double residual_arcsec = 0.0;  // observed minus fitted (V(+) − V(−))/(2·kI·ω), arcsec
};

// The solution of (*) over one set of equations (one rate, or all rates together).
struct GyroMisalignmentFit {
  GyroMisalignmentAngles angles;
  std::size_t equation_count = 0;  // position pairs used
  std::size_t degrees_of_freedom = 0;
  Figure residual_rms;  // arcsec
  std::vector<GyroMisalignmentResidual> residuals;
};

struct GyroMisalignmentRateResult {
  double rate_dps = 0.0;  // |ω|
  GyroMisalignmentFit fit;
};

struct GyroMisalignmentResult {
  GyroMisalignmentFit combined;                     // least squares over every rate's equations, in angle units
  std::vector<GyroMisalignmentRateResult> by_rate;  // increasing |ω|
  std::string output_unit;
  double scale_factor = 0.0;
  std::vector<std::string> warnings;  // e.g. every output equal (a stuck channel)
};

// The JSON of one solution (the angles, equation_count, degrees_of_freedom, residual_rms and the
// residuals) and of the solution at each rate (with rate_dps), for the spec's fields.
nlohmann::json gyro_fit_json(const GyroMisalignmentFit& fit);
nlohmann::json by_rate_json(const GyroMisalignmentResult& result);

// The procedure's one description (src/procedures/gyro_misalignment_spec.cc):
// `inertest misalignment gyro POSITIONS`, plan kind "gyro_misalignment".
ProcedureSpec gyro_misalignment_spec();

// Separates the angles at every rate (rows grouped by |rate_dps|) and over all rates together.
// Uncertainties (1 sigma, from the residuals) are given where there are more equations than
// unknowns. A position read again is another equation (its k-th row at +ω with its k-th at −ω).
// Throws Error (located at the row's file and line where known) for: a zero rate, a position with
// a row at one direction and none to pair it with at the other, and a set of positions at a rate
// that cannot separate the angles (the message names the angles).
GyroMisalignmentResult gyro_misalignment(std::span<const GyroMisalignmentRow> rows,
                                         const GyroMisalignmentOptions& options);

// Outputs of the paper's five positions at one rate: V1 (α, β) = (0, 0), V2 (0, 180°),
// V3 (180°, 180°), V4 (90°, 180°), V5 (0, 90°); index 0 is V1.
struct FivePositionOutputs {
  std::array<double, 5> plus{};   // at +ω
  std::array<double, 5> minus{};  // at −ω
};

// The paper's closed forms (reference README §2), angles in rad:
//   Δθy0 = [V2(+) − V2(−) − V1(+) + V1(−)] / (4·kI·ω)
//   Δθx0 = [2V5(+) − 2V5(−) − V2(+) + V2(−) − V1(+) + V1(−)] / (4·kI·ω)
//   Δθy1 = [V1(−) − V1(+) − V3(+) + V3(−)] / (4·kI·ω)
//   Δθy2 = [V3(+) − V3(−) − V2(+) + V2(−)] / (4·kI·ω)
//   Δθz2 = [2V4(+) − 2V4(−) − V3(+) + V3(−) − V2(+) + V2(−)] / (4·kI·ω)
// Returns {Δθy0, Δθx0, Δθy1, Δθy2, Δθz2}. ω > 0 in deg/s, kI nonzero in output per deg/s.
std::array<double, 5> five_position_misalignment(const FivePositionOutputs& outputs, double scale_factor,
                                                 double rate_dps);

}  // namespace inertest

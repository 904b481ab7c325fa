// Input-axis misalignment of an accelerometer by the multi-position gravity test (the
// misalignment paper: Li Wei, Ren Shunqing, Zhao Hongbo, "misalignment angle separation of inertial
// instruments", HIT; core/citations.h).
//
// The input axis lies horizontal on a vertical reference face and is turned β about the face
// normal. The paper's output model:
//   V = V0 + kI·(−Δθy0 − Δθy1 + Δθz2·sinβ − Δθy2·cosβ)
// With β = 0, 90°, 180°, 270° the paper's closed forms are
//   Δθy2 = (V(π) − V(0)) / (2·kI)        Δθz2 = (V(π/2) − V(3π/2)) / (2·kI)
// (four_position_misalignment below). accelerometer_misalignment() fits the model by least squares
// for any set of β that identifies Δθy2 and Δθz2 (the constant V0 − kI·(Δθy0 + Δθy1) is a third
// unknown per run), run by run, and combines the runs by their mean and its standard error.
//
// Units of this header: β in deg, kI in output units per g, angles reported in arcsec.
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

struct AccelerometerMisalignmentRow {
  double beta_deg = 0.0;  // turn about the reference face normal
  double output = 0.0;    // mean output at that position, output units
  long run = 1;           // runs are separated by this number
  std::size_t line = 0;   // 1-based line in AccelerometerMisalignmentOptions::source, 0 if none
};

struct AccelerometerMisalignmentOptions {
  double scale_factor = 0.0;      // kI, output units per g; must be finite and nonzero
  std::string output_unit = "1";  // for the report only
  std::string source;             // file the rows came from, for error locations

  // Throws Error for a zero or non-finite scale factor or an unknown output unit.
  void validate() const;
};

struct AccelerometerMisalignmentAngles {
  Figure delta_theta_y2;  // arcsec
  Figure delta_theta_z2;  // arcsec
  Figure misalignment;    // γ = √(Δθy2² + Δθz2²), arcsec

  nlohmann::json to_json() const;
};

struct AccelerometerMisalignmentRun {
  long run = 1;
  AccelerometerMisalignmentAngles angles;  // uncertainty from the residuals when over-determined
  std::size_t position_count = 0;
  std::size_t degrees_of_freedom = 0;
  Figure residual_rms;  // output units
};

struct AccelerometerMisalignmentResult {
  // Mean over the runs; uncertainty the standard error of the mean over runs (two runs or more),
  // or the single run's least-squares uncertainty.
  AccelerometerMisalignmentAngles combined;
  std::vector<AccelerometerMisalignmentRun> by_run;  // in order of first appearance
  std::string output_unit;
  double scale_factor = 0.0;
  std::vector<std::string> warnings;  // e.g. every output equal (a stuck channel)
};

// The JSON of the solution of each run (the angles, run, position_count, degrees_of_freedom,
// residual_rms), for the spec's fields.
nlohmann::json by_run_json(const AccelerometerMisalignmentResult& result);

// The procedure's one description (src/procedures/accelerometer_misalignment_spec.cc):
// `inertest misalignment accelerometer POSITIONS`, plan kind "accelerometer_misalignment".
ProcedureSpec accelerometer_misalignment_spec();

// Throws Error (located at the row's file and line where known) for a repeated β within a run, and
// for a run whose positions cannot separate Δθy2 and Δθz2 (naming the angles).
AccelerometerMisalignmentResult accelerometer_misalignment(std::span<const AccelerometerMisalignmentRow> rows,
                                                           const AccelerometerMisalignmentOptions& options);

// The paper's closed forms, angles in rad: returns {Δθy2, Δθz2} from V(0), V(π/2), V(π), V(3π/2).
// Throws Error for an output that is not finite or a scale factor that is zero or not finite.
std::array<double, 2> four_position_misalignment(double v_0, double v_90, double v_180, double v_270,
                                                 double scale_factor);

}  // namespace inertest

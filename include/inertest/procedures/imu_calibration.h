// IMU triad calibration without a precision table (issue 18), the method of Tedaldi, Pretto and
// Menegatti, "A robust and easy to implement method for IMU calibration without external
// equipments", ICRA 2014: the IMU is put by hand in many static orientations, with rotations
// between them.
//
// The model (the paper's eqs. for the accelerometer and gyro triads), for each triad:
//   input = T K (output - b),
// with b the bias (output unit), K = diag(1 / scale_factor) (scale_factor in output unit per input
// unit) and T the non-orthogonality. Convention of the reported `misalignment` M (rad): T = I + M,
// so M's diagonal is 0 and M[i][j] takes out the small angle θ by which sensing axis i leans toward
// frame axis j: that axis reads θ of axis j's input, and M[i][j] = −θ. The accelerometer's T is
// upper-triangular (M[0][1], M[0][2], M[1][2] free): the frame's z axis is the accelerometer's z
// axis, and the accelerometer's y axis lies in the frame's y-z plane. The gyro's T is full (its six
// off-diagonals free, which also holds the gyro triad's rotation with respect to that frame).
//
// Steps: static intervals from the moving variances of both triads against thresholds that a
// multiple of the record's own quietest variances sets; the accelerometer's nine parameters by
// Gauss-Newton on |T K (a_i - b)| = g over the static means a_i (started from an axis-aligned
// ellipsoid fit, so raw counts with offsets of about 32768 need no guess); the gyro's bias as the
// mean of the statics, then its nine parameters by Gauss-Newton on the gravity direction after
// each rotation, integrated with RK4 on the attitude quaternion from the one before. Covariances
// are s^2 (J^T J)^-1 at the solution, s^2 the residual variance.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "inertest/core/units.h"

namespace inertest {

struct ProcedureSpec;
ProcedureSpec imu_calibration_spec();
ProcedureSpec imu_apply_spec();

using Vector3 = std::array<double, 3>;
using Matrix3 = std::array<Vector3, 3>;

// One IMU record: time (s) and the six outputs, in the record's units, of equal length.
struct ImuRecord {
  std::string source;  // the file, for messages
  std::vector<std::size_t> lines;  // the file line of each sample of a text record (empty: not known)
  std::vector<double> time_s;
  std::array<std::vector<double>, 3> accelerometer;
  std::array<std::vector<double>, 3> gyro;
  // The output unit a record of named channels stores for each triad's channels (accelerometer,
  // gyro; "" where none is stored), as imu_output_unit takes it.
  std::array<std::string, 2> stored_units;
};

// The output unit of a triad whose record stores none and whose options give none.
inline constexpr const char* kUnstatedOutputUnit = "count";

struct ImuCalibrationOptions {
  std::string columns = "time_s,ax,ay,az,gx,gy,gz";  // time, accelerometer x y z, gyro x y z
  // The record's output units; "" (the default): the unit its channels store, else kUnstatedOutputUnit.
  std::string accelerometer_unit;
  std::string gyro_unit;
  double gravity_m_s2 = constants::kStandardGravity;  // the site's gravity magnitude
  double static_window_s = 1.0;      // the moving-variance window
  double static_threshold = 6.0;     // the threshold, as a multiple of the quietest windows' variance
  double static_minimum_s = 3.0;     // a shorter still interval is refused
  double outlier_false_alarm = 1e-3;  // the chance that a record of good statics loses one to the outlier test
  std::size_t minimum_statics = 9;   // fewer accepted statics is an error
  std::string export_file;           // "" : no calibration file written

  void validate() const;
};

// A triad's calibration; every figure with its 1-sigma uncertainty, unless a fit of as many
// observations as parameters gives none (uncertainty_known false; the JSON has no "uncertainty").
struct TriadCalibration {
  Vector3 bias{};                  // output unit
  Vector3 bias_uncertainty{};
  Vector3 scale_factor{};          // output unit per input unit
  Vector3 scale_factor_uncertainty{};
  Matrix3 misalignment{};          // rad, M = T - I (see the header comment)
  Matrix3 misalignment_uncertainty{};
  bool uncertainty_known = true;
  std::string output_unit;
  std::string input_unit;          // "m/s^2" or "rad/s"

  // The input (m/s^2, rad/s) of one output sample: (I + M) diag(1/scale_factor) (output - bias).
  Vector3 apply(const Vector3& output) const;
};

// A still interval found in the record, accepted or refused (and why).
struct StaticInterval {
  double start_s = 0.0;
  double end_s = 0.0;
  std::size_t first = 0;  // sample index, [first, last)
  std::size_t last = 0;
  bool accepted = false;
  std::string reason;     // why it was refused, "" when accepted
  Vector3 accelerometer_mean{};  // output unit
  Vector3 gyro_mean{};
  double gravity_residual_m_s2 = 0.0;   // |calibrated mean| - g (accepted)
  // The angle between the gravity direction and the one the gyro carried over from the previous
  // accepted static (none for the first).
  std::optional<double> direction_residual_rad;
};

struct ImuCalibrationResult {
  TriadCalibration accelerometer;
  TriadCalibration gyro;
  std::vector<StaticInterval> static_intervals;
  double accelerometer_residual_rms_m_s2 = 0.0;
  double gyro_residual_rms_rad = 0.0;
  double accelerometer_noise_variance = 0.0;  // the quietest windows' variance (output unit^2, summed over the axes)
  double gyro_noise_variance = 0.0;
  double gravity_m_s2 = 0.0;  // the gravity it was made at (options.gravity_m_s2)
  std::vector<std::string> warnings;
};

// The calibration file (`--export`, read by `inertest imu-apply`): {"procedure": "imu_calibration",
// "model", "gravity": {"value", "unit": "m/s^2"} (the gravity it was made at), "accelerometer", "gyro"},
// each triad as the result's JSON gives it:
// {"bias": {"value": [x, y, z], "unit", "uncertainty": [...]}, "scale_factor": {the same, unit
// "<output>/(<input>)"}, "misalignment": {"value": 3x3, "unit": "rad", "uncertainty": 3x3}}.
nlohmann::json triad_json(const TriadCalibration& triad);
nlohmann::json calibration_file_json(const ImuCalibrationResult& result);
// A calibration file read: its triads (accelerometer, gyro), and the gravity it was made at (none in a
// file written before inertest stated it, or in imu-calibration's --json output).
struct ImuCalibrationFile {
  std::array<TriadCalibration, 2> triads;
  std::optional<double> gravity_m_s2;
};
// Reads a calibration file, or any JSON object with the keys "accelerometer" and "gyro" as above (the
// --json output of imu-calibration). Throws Error naming the file and the key that is wrong.
ImuCalibrationFile read_imu_calibration(const std::string& path);

// The record's columns named by `columns` (a comma list of seven selectors: time, ax, ay, az, gx,
// gy, gz, by header name or 1-based position): a text record, or a record of named channels (MAT,
// HDF5, TDMS; io/channel_record.h). Errors name the file, line and column (or channel).
ImuRecord read_imu_record(const std::string& path, const std::string& columns);

// The output unit of the record's triad (0 the accelerometer, 1 the gyro): `given`, else the unit its
// channels store, else kUnstatedOutputUnit. A `given` that is not the stored unit is an Error naming
// both (a deg/s gyro calibrated as count reported 57.3 count/(rad/s)).
std::string imu_output_unit(const ImuRecord& record, std::size_t triad, const std::string& given);

// An IMU that counts pulses per sample interval (delta angles or delta velocities in pulses: an
// output unit of pulse or pulses, core/units.h counts_pulses) gives rates at its sample rate: the
// samples of the record's triad (0 the accelerometer, 1 the gyro) whose output unit, imu_output_unit
// of `given`, counts pulses are multiplied by the record's mean sample rate, and the triad's unit
// becomes pulse/s, which the record then stores. A scale factor in pulse/s per rad/s is the pulse/rad
// of a data sheet; in counts per interval it changed with the logging rate. Returns the triad's
// output unit as the record now holds it.
std::string imu_pulse_counts_as_rates(ImuRecord& record, std::size_t triad, const std::string& given);

struct StaticDetection {
  std::vector<StaticInterval> intervals;
  double accelerometer_noise_variance = 0.0;  // the median of the quietest tenth of the windows
  double gyro_noise_variance = 0.0;
};

// The still intervals of the record: where the centred moving variance (summed over the axes) of
// the accelerometer and of the gyro are both below options.static_threshold times the median of
// their quietest tenth of the windows (the interval is the windows' centres); refused when shorter
// than static_minimum_s.
StaticDetection detect_static_intervals(const ImuRecord& record, const ImuCalibrationOptions& options);

// The whole calibration. Throws Error (naming the record) when fewer than minimum_statics statics are
// accepted or the orientations cannot identify the model, and (naming its line) at a gap in the time
// stamps, a step of more than 1.5 median steps as `inspect` finds one, inside a rotation the gyro's fit
// integrates; a gap elsewhere is a warning.
ImuCalibrationResult calibrate_imu(const ImuRecord& record, const ImuCalibrationOptions& options);

}  // namespace inertest

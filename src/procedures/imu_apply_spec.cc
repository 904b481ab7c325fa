// Applying an IMU triad calibration (issue 18), declared once (issue 22): `inertest imu-apply CALIB
// RECORD`, the plan kind "imu_apply", its JSON, text, report and Python function come from this
// file. The model is that of procedures/imu_calibration.h (Tedaldi, Pretto and Menegatti, ICRA 2014).
#include <optional>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/citations.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/io/atomic_write.h"
#include "inertest/procedures/imu_calibration.h"

namespace inertest {
namespace {

struct ImuApplyOptions {
  std::string columns = ImuCalibrationOptions().columns;
  // The record's output units; "" (the default): the unit its channels store, else the calibration's.
  std::string accelerometer_unit;
  std::string gyro_unit;
  // None: the gravity the calibration was made at, else the standard gravity.
  std::optional<double> gravity_m_s2;
  std::string output_file;  // "" : the calibrated record is not written

  // The options of the static intervals' detection: imu-calibration's defaults at this gravity.
  ImuCalibrationOptions detection() const {
    ImuCalibrationOptions options;
    options.gravity_m_s2 = gravity_m_s2.value_or(constants::kStandardGravity);
    return options;
  }
  void validate() const { detection().validate(); }
};

struct ImuApplyResult {
  std::size_t samples = 0;
  std::size_t static_intervals = 0;
  // Over the statics; none without one (their 0 passed every limit on a record never checked).
  std::optional<Figure> gravity_residual_rms;  // | calibrated specific force | - g
  std::optional<Figure> rest_rate_rms;         // | calibrated rate |
  std::vector<std::string> warnings;
};

ImuApplyResult apply_imu_calibration(const std::array<TriadCalibration, 2>& calibration, const ImuRecord& record,
                                     const ImuApplyOptions& options) {
  const auto sample = [&](const std::array<std::vector<double>, 3>& columns, std::size_t i) {
    return Vector3{columns[0][i], columns[1][i], columns[2][i]};
  };
  ImuApplyResult result;
  result.samples = record.time_s.size();
  double gravity_squares = 0.0, rate_squares = 0.0;
  const ImuCalibrationOptions detection = options.detection();
  for (const StaticInterval& interval : detect_static_intervals(record, detection).intervals) {
    if (!interval.accepted) continue;
    ++result.static_intervals;
    const Vector3 a = calibration[0].apply(interval.accelerometer_mean);
    const Vector3 w = calibration[1].apply(interval.gyro_mean);
    gravity_squares += std::pow(std::hypot(a[0], a[1], a[2]) - detection.gravity_m_s2, 2);
    rate_squares += w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  }
  if (result.static_intervals == 0) {
    result.warnings.emplace_back("no static interval in the record: the calibration is applied but not checked");
  } else {
    const auto statics = static_cast<double>(result.static_intervals);
    result.gravity_residual_rms = Figure{std::sqrt(gravity_squares / statics), "m/s^2", std::nullopt};
    result.rest_rate_rms = Figure{std::sqrt(rate_squares / statics), "rad/s", std::nullopt};
  }
  // Written last, once everything that can fail has run: a failed run leaves no file (nor a partial one).
  if (!options.output_file.empty()) {
    std::string text = "time_s,ax_m_s2,ay_m_s2,az_m_s2,gx_rad_s,gy_rad_s,gz_rad_s\n";
    for (std::size_t i = 0; i < record.time_s.size(); ++i) {
      const Vector3 a = calibration[0].apply(sample(record.accelerometer, i));
      const Vector3 w = calibration[1].apply(sample(record.gyro, i));
      // The time to 16 digits, a microsecond of an epoch stamp (at 9 digits, 1.7e9 s stamps were 100 s
      // apart), without the last bit's noise of a converted one (1.4000000000000001); the calibrated
      // samples to 9 digits, beyond any IMU's resolution.
      text += fmt::format("{:.16g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", record.time_s[i], a[0], a[1], a[2],
                          w[0], w[1], w[2]);
    }
    write_file_atomically(options.output_file, text);
  }
  return result;
}

// Brings each triad of `record` to its calibration's output unit, returning the warnings. The
// record's unit is the one given, else the one it stores, else the calibration's; pulses counted
// per sample interval are read as pulse/s, as imu-calibration reads them. A unit other than the
// calibration's is an Error, except for calibrations made before, whose figures apply to the
// samples as they are, said in a warning: in count (before records' units were read), to a record
// in any unit, and in pulse (counts per sample interval, before they were read as pulse/s), to a
// record in pulse. A calibration in pulse/s applied to a
// record that states no unit is an Error: its samples may be counts or rates.
std::vector<std::string> read_in_calibration_units(ImuRecord& record,
                                                   const std::array<TriadCalibration, 2>& calibration,
                                                   const ImuApplyOptions& options) {
  std::vector<std::string> warnings;
  for (std::size_t triad = 0; triad < 2; ++triad) {
    const char* name = triad == 0 ? "accelerometer" : "gyro";
    const std::string& unit = calibration[triad].output_unit;
    const std::string& given = triad == 0 ? options.accelerometer_unit : options.gyro_unit;
    const bool stated = !given.empty() || !record.stored_units[triad].empty();
    const std::string& taken = stated ? given : unit;  // imu_output_unit prefers the stored unit to ""
    const std::string read = imu_output_unit(record, triad, taken);
    if (unit == kUnstatedOutputUnit) {
      // Compared as text: count and pulse are one unit to core/units.h, yet pulses count per interval.
      if (read != unit) {
        warnings.push_back(
            fmt::format("the calibration's {} output unit is count, the record's {}: its figures are "
                        "applied to the samples as they are (imu-calibration now calibrates in the "
                        "record's unit)",
                        name, read));
      }
      continue;
    }
    if (counts_pulses(unit) && counts_pulses(read)) {
      warnings.push_back(
          fmt::format("the calibration's {} output unit is {}, counts per sample interval (made before "
                      "imu-calibration read them as pulse/s): its figures are applied to the samples "
                      "as they are, right only at its record's sample rate; calibrate again",
                      name, unit));
      continue;
    }
    if (!stated && same_unit(unit, "pulse/s")) {
      throw Error(SourceLocation{record.source, 0, 0},
                  fmt::format("the calibration's {0} output unit is pulse/s and the record states none: give it "
                              "(--{0}-unit pulse for counts per sample interval, pulse/s for rates; {0}_unit)",
                              name));
    }
    const std::string rate = imu_pulse_counts_as_rates(record, triad, taken);
    if (!same_unit(rate, unit)) {
      throw Error(SourceLocation{record.source, 0, 0},
                  fmt::format("the record's {0} output unit is {1}{2}, the calibration's {3}: give the record's unit "
                              "(--{0}-unit; {0}_unit) or a calibration made in it",
                              name, read, rate == read ? "" : " (read as " + rate + ")", unit));
    }
  }
  return warnings;
}

}  // namespace

ProcedureSpec imu_apply_spec() {
  using Options = ImuApplyOptions;
  using Result = ImuApplyResult;
  return ProcedureDefinition<Options, Result>(
             "imu_apply", "IMU triad calibration applied", citations::kImuCalibrationPaper,
             "applies the calibration that `inertest imu-calibration --export` wrote (CALIB, or its --json\n"
             "output) to an IMU record: input = (I + M) diag(1/scale_factor) (output - bias) for each triad,\n"
             "written to --output FILE as time_s,ax_m_s2,ay_m_s2,az_m_s2,gx_rad_s,gy_rad_s,gz_rad_s, and\n"
             "checked on the record's static intervals: the rms of |specific force| - g and of |rate|.")
      .chinese_title("惯性测量单元标定结果应用")
      .example({"examples/imu_calibration/calibration.json", "examples/imu_calibration/tumble.csv"})
      .input(InputSpec("calibration", "the calibration (imu-calibration --export)").read_from_file("CALIB", "calibration"))
      .input(InputSpec("record", "IMU record: time and six outputs").read_from_file("RECORD", "file"))
      .parameter(ParameterSpec("columns", "time, ax, ay, az, gx, gy, gz: header names or 1-based positions"),
                 &Options::columns)
      .parameter(ParameterSpec("accelerometer_unit", "the record's accelerometer output unit (default: the unit its "
                                                     "channels store, else the calibration's; pulse: read as pulse/s)"),
                 &Options::accelerometer_unit)
      .parameter(ParameterSpec("gyro_unit", "the record's gyro output unit (default: the unit its channels store, else "
                                            "the calibration's; pulse: read as pulse/s)"),
                 &Options::gyro_unit)
      .parameter(ParameterSpec("gravity_m_s2", "local gravity (default: the gravity the calibration states, else the "
                                               "standard 9.80665)")
                     .unit_is("m/s^2")
                     .command_line_name_is("gravity")
                     .site_gives("gravity_m_s2"),
                 &Options::gravity_m_s2)
      .parameter(ParameterSpec("output", "write the calibrated record to FILE (.csv); in a plan a relative FILE is "
                                         "beside results.json").writes_file(),
                 &Options::output_file)
      .field({"gravity_residual_rms", FieldRole::headline, "rms of |specific force| - g over the statics",
              "静止区间比力模与重力之差均方根", ""},
             &Result::gravity_residual_rms)
      .field({"rest_rate_rms", FieldRole::headline, "rms of |rate| over the statics", "静止区间角速度模均方根", ""},
             &Result::rest_rate_rms)
      .field({"samples", FieldRole::detail, "samples", "样本数", ""}, &Result::samples)
      .field({"static_intervals", FieldRole::detail, "static intervals", "静止区间数", ""}, &Result::static_intervals)
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &Result::warnings)
      .unit_of("gravity_residual_rms", "m/s^2")
      .unit_of("rest_rate_rms", "rad/s")
      .compute([](const ProcedureCall& call, Options options) {
        // In a plan, into the campaign's staging directory: beside results.json once every step has run.
        if (!options.output_file.empty()) options.output_file = call.output_path(options.output_file);
        const ImuCalibrationFile file = read_imu_calibration(call.files.at("calibration"));
        const std::array<TriadCalibration, 2>& calibration = file.triads;
        ImuRecord record = read_imu_record(call.files.at("record"), options.columns);
        std::vector<std::string> warnings = read_in_calibration_units(record, calibration, options);
        // The accelerometer's scale factors are in proportion to the gravity the calibration took: checked
        // at another, every static shows the difference (9.81744 against the default 9.80665 read as a
        // residual of 0.0108 m/s^2 for 0.0002).
        if (!options.gravity_m_s2) {
          if (!file.gravity_m_s2) {
            warnings.emplace_back("the calibration states no gravity (imu-calibration's --json output, or an export "
                                  "written before exports stated it): checked at the standard 9.80665 m/s^2; give "
                                  "--gravity for the site's");
          }
          options.gravity_m_s2 = file.gravity_m_s2;
        } else if (file.gravity_m_s2 && std::abs(*options.gravity_m_s2 - *file.gravity_m_s2) > 1e-6 * *file.gravity_m_s2) {
          warnings.push_back(fmt::format("the calibration was made at a gravity of {:.8g} m/s^2, and is checked here "
                                         "at {:.8g} m/s^2: the gravity residual holds the difference",
                                         *file.gravity_m_s2, *options.gravity_m_s2));
        }
        ImuApplyResult result = apply_imu_calibration(calibration, record, options);
        result.warnings.insert(result.warnings.begin(), warnings.begin(), warnings.end());
        return result;
      });
}

}  // namespace inertest

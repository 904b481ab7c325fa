// IMU triad calibration without a precision table (issue 18), declared once (issue 22): the command
// `inertest imu-calibration`, the plan kind "imu_calibration", the JSON, the text, the report and the
// Python function come from this file. The method and the model (Tedaldi, Pretto and Menegatti,
// ICRA 2014) are in procedures/imu_calibration.h.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "inertest/core/citations.h"
#include "inertest/core/json_text.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/io/atomic_write.h"
#include "inertest/procedures/imu_calibration.h"

namespace inertest {
namespace {

using Options = ImuCalibrationOptions;
using Result = ImuCalibrationResult;

nlohmann::json interval_rows(const Result& result) {
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t i = 0; i < result.static_intervals.size(); ++i) {
    const StaticInterval& interval = result.static_intervals[i];
    nlohmann::json row = {{"start", Figure{interval.start_s, "s", std::nullopt}},
                          {"end", Figure{interval.end_s, "s", std::nullopt}},
                          {"accepted", interval.accepted}};
    if (interval.accepted) {
      row["gravity_residual"] = Figure{interval.gravity_residual_m_s2, "m/s^2", std::nullopt};
      if (interval.direction_residual_rad) {
        row["direction_residual"] = Figure{*interval.direction_residual_rad, "rad", std::nullopt};
      }
    } else {
      row["reason"] = interval.reason;
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

// The residual of each accepted static at its start: the gravity magnitude's, or the gravity
// direction's after the rotation into it (from the second accepted static on).
nlohmann::json residual_curve(const Result& result, bool direction) {
  nlohmann::json points = nlohmann::json::array();
  for (const StaticInterval& interval : result.static_intervals) {
    if (!interval.accepted || (direction && !interval.direction_residual_rad)) continue;
    points.push_back({{"time", Figure{interval.start_s, "s", std::nullopt}},
                      {"residual", direction ? Figure{*interval.direction_residual_rad, "rad", std::nullopt}
                                             : Figure{interval.gravity_residual_m_s2, "m/s^2", std::nullopt}}});
  }
  return points;
}

// A triad's field (triad_json): its bias and scale factors are [x, y, z], its misalignment 3x3.
FieldSpec triad_field(FieldSpec field) {
  field.array_figures = {{"bias", 1}, {"scale_factor", 1}, {"misalignment", 2}};
  return field;
}

}  // namespace

ProcedureSpec imu_calibration_spec() {
  return ProcedureDefinition<Options, Result>(
             "imu_calibration", "IMU triad calibration in static orientations", citations::kImuCalibrationPaper,
             "the accelerometer and gyro triads' bias, scale factors and non-orthogonality from one record of\n"
             "an IMU held still by hand in many (9 or more) orientations with rotations between them: the\n"
             "statics where both triads' moving variances stay below a multiple of the record's quietest\n"
             "ones; the accelerometer by |T K (a - b)| = g over the statics; the gyro's bias from the\n"
             "statics, its T K by the gravity direction after each rotation (RK4 on the quaternion, the\n"
             "rate at each step's middle from the cubic through four samples: fourth order). Each gyro\n"
             "sample is taken as the instantaneous rate at its time stamp.\n"
             "Model input = (I + M) diag(1/scale_factor) (output - bias); M (rad) upper-triangular for the\n"
             "accelerometer (the frame's z axis is its z axis, its y axis in the frame's y-z plane), full for\n"
             "the gyro; M[i][j] = -theta for sensing axis i leaning by theta toward frame axis j.\n"
             "The accelerometer's scale factors are taken positive (gravity's magnitude cannot tell a sign);\n"
             "the gyro's carry their signs, relative to them (a reversed axis is negative).\n"
             "RECORD is a text record or a .mat, HDF5 or TDMS file; --columns names its time (s) and six outputs. --export FILE writes\n"
             "the calibration that `inertest imu-apply` applies.")
      .chinese_title("惯性测量单元多位置标定")
      .report_method(
          "The IMU is held still by hand in many orientations, with rotations between them. The static intervals "
          "are found where the moving variances of both triads stay below a multiple of the record's own quietest "
          "ones. The accelerometer's bias, scale factors and non-orthogonality are fitted so that the "
          "calibrated specific force of every static interval has the magnitude of the local gravity; the gyro's "
          "bias is the mean of the static intervals, and its scale factors and non-orthogonality are fitted so that "
          "the rotation integrated (RK4 on the quaternion) between two static intervals turns the gravity direction "
          "of the first into that of the second (Tedaldi, Pretto and Menegatti, ICRA 2014).",
          "用手将惯性测量单元依次静置于多个姿态，姿态之间转动。以加速度计和陀螺的滑动方差均低于记录自身最小滑动方差的若干倍判定静止区间。"
          "加速度计的零偏、标度因数和非正交误差按各静止区间标定后比力的模等于当地重力加速度拟合；陀螺零偏取静止区间均值，"
          "其标度因数和非正交误差按两静止区间之间积分（四元数四阶龙格-库塔）的转动把前一区间的重力方向转到后一区间的重力方向拟合"
          "（Tedaldi、Pretto、Menegatti，ICRA 2014）。")
      .example({"examples/imu_calibration/tumble.csv"})
      .input(InputSpec("record", "IMU record: time and six outputs").read_from_file("RECORD", "file"))
      .parameter(ParameterSpec("columns", "time, ax, ay, az, gx, gy, gz: header names or 1-based positions"),
                 &Options::columns)
      .parameter(ParameterSpec("accelerometer_unit",
                               "the record's accelerometer output unit (default: the unit its channels store, else "
                               "count; pulse: delta velocities counted per sample interval, read as pulse/s)"),
                 &Options::accelerometer_unit)
      .parameter(ParameterSpec("gyro_unit", "the record's gyro output unit (default: the unit its channels store, else count; "
                                            "pulse: delta angles counted per sample interval, read as pulse/s)"),
                 &Options::gyro_unit)
      .parameter(ParameterSpec("gravity_m_s2", "local gravity")
                     .unit_is("m/s^2")
                     .command_line_name_is("gravity")
                     .site_gives("gravity_m_s2"),
                 &Options::gravity_m_s2)
      .parameter(ParameterSpec("static_window_s", "moving-variance window").unit_is("s").command_line_name_is("static-window"),
                 &Options::static_window_s)
      .parameter(ParameterSpec("static_threshold", "still below this multiple of the quietest windows' variance"),
                 &Options::static_threshold)
      .parameter(ParameterSpec("static_minimum_s", "a static interval lasts at least").unit_is("s").command_line_name_is(
                     "static-minimum"),
                 &Options::static_minimum_s)
      .parameter(ParameterSpec("outlier_false_alarm", "chance that a record of good statics loses one to the outlier test "
                                                      "(studentised residual from the fit without it)"),
                 &Options::outlier_false_alarm)
      .parameter(ParameterSpec("minimum_statics", "fewer accepted static intervals is an error"), &Options::minimum_statics)
      .parameter(ParameterSpec("export", "write the calibration to FILE (.json) for imu-apply (in a plan a relative FILE is "
                                           "beside results.json)").writes_file(), &Options::export_file)
      .field_from(triad_field({"accelerometer", FieldRole::detail, "accelerometer triad", "加速度计组件", "Tedaldi et al. 2014"}),
                  [](const Result& result) { return triad_json(result.accelerometer); })
      .field_from(triad_field({"gyro", FieldRole::detail, "gyro triad", "陀螺组件", "Tedaldi et al. 2014"}),
                  [](const Result& result) { return triad_json(result.gyro); })
      .field_from({"residual_rms", FieldRole::detail, "rms residual", "残差均方根", ""},
                  [](const Result& result) {
                    return nlohmann::json{
                        {"accelerometer", Figure{result.accelerometer_residual_rms_m_s2, "m/s^2", std::nullopt}},
                        {"gyro", Figure{result.gyro_residual_rms_rad, "rad", std::nullopt}}};
                  })
      .field_from({"static_intervals", FieldRole::table, "static intervals", "静止区间", ""}, interval_rows)
      .figure_from({"accelerometer_noise_variance", FieldRole::detail, "accelerometer noise variance (quietest windows)",
                    "加速度计最小滑动方差", ""},
                   [](const Result& result) {
                     return Figure{result.accelerometer_noise_variance, result.accelerometer.output_unit + "^2", std::nullopt};
                   })
      .figure_from({"gyro_noise_variance", FieldRole::detail, "gyro noise variance (quietest windows)", "陀螺最小滑动方差", ""},
                   [](const Result& result) {
                     return Figure{result.gyro_noise_variance, result.gyro.output_unit + "^2", std::nullopt};
                   })
      .field_from({"gravity_residuals", FieldRole::curve, "gravity magnitude residual of each static interval",
                   "各静止区间重力模残差", "", {"time", "residual"}},
                  [](const Result& result) { return residual_curve(result, false); })
      .field_from({"direction_residuals", FieldRole::curve, "gravity direction residual after each rotation",
                   "各次转动后重力方向残差", "", {"time", "residual"}},
                  [](const Result& result) { return residual_curve(result, true); })
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &Result::warnings)
      .compute([](const ProcedureCall& call, Options options) {
        ImuRecord record = read_imu_record(call.files.at("record"), options.columns);
        options.accelerometer_unit = imu_pulse_counts_as_rates(record, 0, options.accelerometer_unit);
        options.gyro_unit = imu_pulse_counts_as_rates(record, 1, options.gyro_unit);
        Result result = calibrate_imu(record, options);
        if (!options.export_file.empty()) {
          write_file_atomically(call.output_path(options.export_file), json_text(calibration_file_json(result), 2) + "\n");
        }
        return result;
      });
}

}  // namespace inertest

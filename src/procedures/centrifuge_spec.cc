// Drift coefficients of a gyro calibrated on a precision centrifuge with a counter-rotating platform
// (the centrifuge paper, core/citations.h; inertest/centrifuge/drift_calibration.h), declared once
// (issue 22): the command `inertest centrifuge`, the plan kind "centrifuge", the JSON, the text and
// the report come from this file.
#include <nlohmann/json.hpp>

#include "inertest/centrifuge/centrifuge_record.h"
#include "inertest/centrifuge/drift_calibration.h"
#include "inertest/core/citations.h"
#include "inertest/core/surface_gravity.h"

namespace inertest {
namespace {

using centrifuge::DriftCalibrationResult;

// The options as the command line and a plan give them: the site in its users' units.
struct CentrifugeInputOptions {
  double radius_m = 1.0;
  std::optional<double> latitude_deg;
  double gravity_m_s2 = constants::kStandardGravity;
  std::optional<double> k1_rad;
  std::optional<double> k2_rad;
  std::optional<double> delta_omega_rad_s;
  bool compensation = true;
  bool estimate_errors = false;

  centrifuge::DriftCalibrationOptions calibration() const {
    centrifuge::DriftCalibrationOptions options;
    options.site.radius_m = radius_m;
    options.site.latitude_rad = latitude_deg.value_or(0.0) * constants::kDegree;
    options.site.gravity_m_s2 = gravity_m_s2;
    options.k1_rad = k1_rad;
    options.k2_rad = k2_rad;
    options.delta_omega_rad_s = delta_omega_rad_s;
    options.compensation = compensation;
    options.estimate_errors = estimate_errors;
    return options;
  }
};

}  // namespace

ProcedureSpec centrifuge_spec() {
  using Options = CentrifugeInputOptions;
  return ProcedureDefinition<Options, DriftCalibrationResult>(
             "centrifuge", "Drift coefficients on a centrifuge",
             "the centrifuge paper, eqs. (2), (5)-(16) and section 6",
             "Drift coefficients D_F, D_I, D_O, D_S, D_II, D_OO, D_SS, D_IO, D_IS, D_OS of a gyro calibrated on a\n"
             "precision centrifuge with a counter-rotating platform, centrifuge errors compensated.\n"
             "FILE is either harmonic amplitudes, header 'accel_g,beta_deg,k0,k1c,k1s,k2c,k2s' (deg/h, one row per\n"
             "g-level and platform angle), or raw samples, header 'accel_g,beta_deg,gamma_deg,output' (output in\n"
             "deg/h, gamma the angle from the input axis to the centripetal direction; analysed over whole\n"
             "revolutions, exact DFT when equally spaced, else least squares). Either may add 'omega_rad_s', the\n"
             "main-axis rate; without it Omega = sqrt(accel_g * gravity / radius). Two g-levels (at four platform\n"
             "angles each, or any set whose design has full rank) identify all ten coefficients.\n"
             "The gravity is the site's, of A = Omega^2 R0 / g: the coefficients are per standard g (9.80665\n"
             "m/s^2), converted from it. The latitude is required while compensating (the Earth rate enters\n"
             "epsilon); without compensation it defaults to 0 and then only enters the Coriolis term. Unmeasured\n"
             "k1, k2, delta-omega are taken as 0 unless --estimate-errors estimates them (two or more g-levels).\n"
             "Outputs: coefficients (1-sigma), residual_rms, centrifuge_errors, influence (per error alone, paper\n"
             "section 6: its magnitude, the shift of each coefficient it causes when left uncompensated =\n"
             "(Phi^T Phi)^-1 Phi^T epsilon_i, and that shift per unit error), runs (residuals).\nSource: " +
                 std::string(citations::kCentrifugePaper) + ".")
      .chinese_title("离心机漂移系数标定")
      .report_method(
          "One platform revolution at each angle β and g-level gives the harmonic amplitudes of eq. (11); stacking "
          "them, Y = Φq + ε (eqs. 13-16) is solved by least squares for the ten drift coefficients, the centrifuge "
          "errors and Earth rate compensated in ε. Coefficients are per standard g (9.80665 m/s²), converted from the "
          "local g of A = Ω²R₀/g.",
          "在各平台角 β 与过载下采集平台一周数据，由谐波分析得式 (11) 的各谐波幅值；组成 Y = Φq + ε（式 13-16），"
          "以最小二乘法求十项漂移系数，离心机误差与地球自转角速度在 ε 中补偿。漂移系数以标准重力加速度 g（9.80665 m/s²）"
          "为单位，由 A = Ω²R₀/g 中的当地 g 换算。")
      .input(InputSpec("file", "harmonic amplitudes or raw samples (CSV with header)").read_from_file("FILE", "file"))
      .parameter(ParameterSpec("radius_m", "centrifuge radius R0 to the gyro").unit_is("m").command_line_name_is("radius"),
                 &Options::radius_m)
      .parameter(ParameterSpec("latitude_deg", "site latitude (north positive)")
                     .unit_is("deg")
                     .command_line_name_is("latitude")
                     .site_gives("latitude_deg"),
                 &Options::latitude_deg)
      .parameter(ParameterSpec("gravity_m_s2", "local gravity")
                     .unit_is("m/s^2")
                     .command_line_name_is("gravity")
                     .site_gives("gravity_m_s2"),
                 &Options::gravity_m_s2)
      .parameter(ParameterSpec("k1_rad", "measured k1 = dtheta_y2t + dtheta_y2(-Omega t)")
                     .unit_is("rad")
                     .command_line_name_is("k1"),
                 &Options::k1_rad)
      .parameter(ParameterSpec("k2_rad", "measured k2 = dtheta_x2t + dtheta_x2(-Omega t)")
                     .unit_is("rad")
                     .command_line_name_is("k2"),
                 &Options::k2_rad)
      .parameter(ParameterSpec("delta_omega_rad_s", "measured platform rate minus main-axis rate")
                     .unit_is("rad/s")
                     .command_line_name_is("delta-omega"),
                 &Options::delta_omega_rad_s)
      .parameter(ParameterSpec("compensation",
                               "compensate the Earth rate and the centrifuge errors in epsilon (false: epsilon = 0, "
                               "the paper's comparison)")
                     .command_line_flag("no-compensation", false),
                 &Options::compensation)
      .parameter(ParameterSpec("estimate_errors", "estimate the unmeasured k1, k2, delta-omega with the coefficients"),
                 &Options::estimate_errors)
      .field_from({"coefficients", FieldRole::headline, "drift coefficients", "漂移系数", "eqs. (13)-(16)"},
                  [](const DriftCalibrationResult& result) { return centrifuge::coefficient_json(result.coefficients); })
      .field({"residual_rms", FieldRole::headline, "rms residual", "残差均方根", "eqs. (13)-(16)"},
             &DriftCalibrationResult::residual_rms)
      .field({"degrees_of_freedom", FieldRole::detail, "degrees of freedom", "自由度", ""},
             &DriftCalibrationResult::degrees_of_freedom)
      .field({"g_levels", FieldRole::detail, "g-levels", "过载档数", ""}, &DriftCalibrationResult::g_levels)
      .field({"compensation", FieldRole::detail, "compensation", "误差补偿", "eq. (16)"},
             &DriftCalibrationResult::compensation)
      .field_from({"centrifuge_errors", FieldRole::detail, "centrifuge errors", "离心机误差", "eqs. (5)-(8)"},
                  centrifuge::centrifuge_errors_json)
      .field_from({"influence", FieldRole::detail, "influence of each error alone", "各误差单独影响", "section 6"},
                  centrifuge::influence_json)
      .field_from({"site", FieldRole::detail, "site", "试验场地", "eq. (2)"},
                  [](const DriftCalibrationResult& result) { return centrifuge::site_json(result.site); })
      .field_from({"runs", FieldRole::curve, "harmonic amplitudes and residuals of each run", "各次谐波幅值与残差",
                   "eqs. (11), (13)-(16)"},
                  centrifuge::runs_json)
      .field_from({"coefficients_g", FieldRole::detail, "coefficients", "系数单位", ""},
                  [](const DriftCalibrationResult&) {
                    return "per standard g (9.80665 m/s^2), converted from the site's gravity of A = Omega^2 R0 / g";
                  })
      .field_from({"source", FieldRole::hidden, "source", "来源", ""},
                  [](const DriftCalibrationResult&) {
                    return std::string(citations::kCentrifugePaper) + ", eqs. (2), (5)-(16) and section 6";
                  })
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &DriftCalibrationResult::warnings)
      .checked_by([](const ProcedureCall&, const Options& options) {
        if (!options.latitude_deg && options.compensation) {
          throw Error("centrifuge: --latitude is required: the Earth rate at the site enters the compensation "
                      "(or pass --no-compensation)");
        }
        check_surface_gravity("gravity_m_s2", options.gravity_m_s2);
        options.calibration().validate();
      })
      .unit_of("residual_rms", "deg/h")
      .compute([](const ProcedureCall& call, const Options& options) {
        const centrifuge::CentrifugeRecord record = centrifuge::read_centrifuge_record(call.files.at("file"));
        DriftCalibrationResult result = centrifuge::calibrate_drift_coefficients(record.runs(), options.calibration());
        if (!options.latitude_deg) result.warnings.emplace_back("no latitude given: 0 deg in the Coriolis term");
        return result;
      });
}

}  // namespace inertest

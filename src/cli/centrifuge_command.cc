// inertest centrifuge FILE [--radius M] [--latitude DEG] [--gravity MS2] [--k1 RAD] [--k2 RAD]
//                          [--delta-omega RADS] [--no-compensation] [--estimate-errors] [--json]
#include <nlohmann/json.hpp>
#include <optional>

#include "command.h"
#include "inertest/core/citations.h"
#include "inertest/centrifuge/centrifuge_record.h"
#include "inertest/centrifuge/drift_calibration.h"
#include "inertest/core/error.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string file;
  double radius_m = 1.0;
  std::optional<double> latitude_deg;
  double gravity_m_s2 = constants::kStandardGravity;
  std::optional<double> k1_rad;
  std::optional<double> k2_rad;
  std::optional<double> delta_omega_rad_s;
  bool no_compensation = false;
  bool estimate_errors = false;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "centrifuge",
      std::string("Drift coefficients D_F, D_I, D_O, D_S, D_II, D_OO, D_SS, D_IO, D_IS, D_OS of a gyro calibrated on a\n"
                  "precision centrifuge with a counter-rotating platform, centrifuge errors compensated.\nSource: ") +
          citations::kCentrifugePaper +
          "; eqs. 2, 5-16; error influence, section 6.\n"
          "FILE is either harmonic amplitudes, header 'accel_g,beta_deg,k0,k1c,k1s,k2c,k2s' (deg/h, one row per\n"
      "g-level and platform angle), or raw samples, header 'accel_g,beta_deg,gamma_deg,output' (output in\n"
      "deg/h, gamma the angle from the input axis to the centripetal direction; analysed over whole\n"
      "revolutions, exact DFT when equally spaced, else least squares). Either may add 'omega_rad_s', the\n"
      "main-axis rate; without it Omega = sqrt(accel_g * gravity / radius). Two g-levels (at four platform\n"
      "angles each, or any set whose design has full rank) identify all ten coefficients.\n"
      "Defaults: radius 1 m, gravity 9.80665 m/s^2 (the site's gravity, of A = Omega^2 R0 / g: pass the local\n"
      "value; the coefficients are per standard g, 9.80665 m/s^2, converted from it). --latitude has no default while "
      "compensating (the Earth rate enters epsilon); with\n"
      "--no-compensation it defaults to 0 and then only enters the Coriolis term. Unmeasured k1, k2,\n"
      "delta-omega are taken as 0 unless --estimate-errors estimates them (two or more g-levels).\n"
      "Outputs: coefficients (deg/h, deg/h/g, deg/h/g^2, 1-sigma), residual_rms (deg/h), centrifuge_errors,\n"
      "influence (per error alone, paper section 6: its magnitude, the shift of each coefficient it causes\n"
      "when left uncompensated = (Phi^T Phi)^-1 Phi^T epsilon_i, and that shift per unit error), runs (residuals).");
  command->add_option("FILE", arguments->file, "harmonic amplitudes or raw samples (CSV with header)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--radius", arguments->radius_m, "centrifuge radius R0 to the gyro, m")->capture_default_str();
  command->add_option("--latitude", arguments->latitude_deg, "site latitude, deg (north positive)");
  command->add_option("--gravity", arguments->gravity_m_s2, "local gravity, m/s^2")->capture_default_str();
  command->add_option("--k1", arguments->k1_rad, "measured k1 = dtheta_y2t + dtheta_y2(-Omega t), rad");
  command->add_option("--k2", arguments->k2_rad, "measured k2 = dtheta_x2t + dtheta_x2(-Omega t), rad");
  command->add_option("--delta-omega", arguments->delta_omega_rad_s,
                      "measured platform rate minus main-axis rate, rad/s");
  command->add_flag("--no-compensation", arguments->no_compensation,
                    "epsilon = 0: no Earth-rate or centrifuge-error compensation (the paper's comparison)");
  command->add_flag("--estimate-errors", arguments->estimate_errors,
                    "estimate the unmeasured k1, k2, delta-omega with the coefficients");
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    centrifuge::DriftCalibrationOptions options;
    options.compensation = !arguments->no_compensation;
    options.estimate_errors = arguments->estimate_errors;
    if (!arguments->latitude_deg && options.compensation) {
      throw Error("centrifuge: --latitude is required: the Earth rate at the site enters the compensation "
                  "(or pass --no-compensation)");
    }
    options.site.radius_m = arguments->radius_m;
    options.site.latitude_rad = arguments->latitude_deg.value_or(0.0) * constants::kDegree;
    options.site.gravity_m_s2 = arguments->gravity_m_s2;
    options.k1_rad = arguments->k1_rad;
    options.k2_rad = arguments->k2_rad;
    options.delta_omega_rad_s = arguments->delta_omega_rad_s;
    options.validate();
    const centrifuge::CentrifugeRecord record = centrifuge::read_centrifuge_record(arguments->file);
    const std::vector<centrifuge::CentrifugeRun> runs = record.runs();
    centrifuge::DriftCalibrationResult result = centrifuge::calibrate_drift_coefficients(runs, options);
    if (!arguments->latitude_deg) {
      result.warnings.emplace_back("no --latitude: 0 deg in the Coriolis term");
    }
    print_result(result.to_json(), result.report(), arguments->json);
    return 0;
  };
}

const bool registered = register_command("centrifuge", setup);

}  // namespace
}  // namespace inertest::cli

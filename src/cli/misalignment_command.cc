// inertest misalignment gyro POSITIONS.csv --scale-factor K [--records] [--json]
// inertest misalignment accelerometer POSITIONS.csv --scale-factor K [--json]
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/core/citations.h"
#include "inertest/misalignment/accelerometer_misalignment.h"
#include "inertest/misalignment/gyro_misalignment.h"
#include "inertest/misalignment/misalignment_files.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string gyro_file;
  bool gyro_records = false;
  GyroMisalignmentOptions gyro;
  std::string accelerometer_file;
  AccelerometerMisalignmentOptions accelerometer;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "misalignment",
      std::string("Separate an instrument's input-axis misalignment from the table's and the fixture's errors.\n"
                  "Angles in arcsec. Source: ") +
          citations::kMisalignmentPaper + ".");
  command->require_subcommand(1);

  CLI::App* gyro = command->add_subcommand(
      "gyro",
      "Gyro on a single-axis rate table, fixture turned beta, gyro turned alpha, table at +w and -w.\n"
      "POSITIONS has the header 'alpha_deg,beta_deg,rate_dps,output': one row per position and\n"
      "direction (sign of rate_dps), output averaged over whole revolutions; any number of rates.\n"
      "With --records, POSITIONS is 'alpha_deg,beta_deg,rate_dps,file' and each file a record with\n"
      "'output' and 'table_angle_deg' or 'time_s'; the tool averages whole revolutions itself.\n"
      "Least squares on V(+) - V(-) = 2 kI w (-dy0 cos b + dx0 sin b - dy1 + dz2 sin a - dy2 cos a).\n"
      "Outputs: delta_theta_y0, delta_theta_x0, delta_theta_y1, delta_theta_y2, delta_theta_z2,\n"
      "misalignment (all rates together), by_rate (the same per rate, with rate_dps).");
  gyro->add_option("POSITIONS", arguments->gyro_file, "CSV of positions (or of records with --records)")
      ->required()
      ->check(CLI::ExistingFile);
  gyro->add_option("--scale-factor", arguments->gyro.scale_factor, "kI, output units per deg/s")->required();
  gyro->add_option("--output-unit", arguments->gyro.output_unit, "instrument output unit, e.g. V")
      ->capture_default_str();
  gyro->add_flag("--records", arguments->gyro_records, "POSITIONS lists raw records to average over whole revolutions");
  gyro->add_flag("--json", arguments->json, "print one JSON object on stdout");

  CLI::App* accelerometer = command->add_subcommand(
      "accelerometer",
      "Accelerometer, input axis horizontal on a vertical face turned beta (4-position gravity test).\n"
      "POSITIONS has the header 'beta_deg,output' and optionally 'run'; any beta that separate the\n"
      "angles (the paper's 0, 90, 180, 270). Outputs: delta_theta_y2, delta_theta_z2, misalignment\n"
      "(mean over runs with its standard error), by_run (the same per run, with run).");
  accelerometer->add_option("POSITIONS", arguments->accelerometer_file, "CSV of positions")
      ->required()
      ->check(CLI::ExistingFile);
  accelerometer->add_option("--scale-factor", arguments->accelerometer.scale_factor, "kI, output units per g")
      ->required();
  accelerometer->add_option("--output-unit", arguments->accelerometer.output_unit, "instrument output unit, e.g. V")
      ->capture_default_str();
  accelerometer->add_flag("--json", arguments->json, "print one JSON object on stdout");

  return [arguments, gyro, accelerometer] {
    if (gyro->parsed()) {
      arguments->gyro.source = arguments->gyro_file;
      arguments->gyro.validate();
      const std::vector<GyroMisalignmentRow> rows = arguments->gyro_records
                                                        ? read_gyro_misalignment_records(arguments->gyro_file)
                                                        : read_gyro_misalignment_positions(arguments->gyro_file);
      const GyroMisalignmentResult result = gyro_misalignment(rows, arguments->gyro);
      print_result(result.to_json(), result.report(), arguments->json);
      return 0;
    }
    if (accelerometer->parsed()) {
      arguments->accelerometer.source = arguments->accelerometer_file;
      arguments->accelerometer.validate();
      const std::vector<AccelerometerMisalignmentRow> rows =
          read_accelerometer_misalignment_positions(arguments->accelerometer_file);
      const AccelerometerMisalignmentResult result = accelerometer_misalignment(rows, arguments->accelerometer);
      print_result(result.to_json(), result.report(), arguments->json);
      return 0;
    }
    return 1;
  };
}

const bool registered = register_command("misalignment", setup);

}  // namespace
}  // namespace inertest::cli

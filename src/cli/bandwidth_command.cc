// inertest bandwidth GAINS.csv [--json]
// inertest bandwidth --records RUNS.csv [--time-column ...] [--output-column ...] [--angle-column ...]
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/core/error.h"
#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/bandwidth_and_delay.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string gains_file;
  std::string records_listing;
  std::string time_column = "time_s";
  std::string output_column = "output";
  std::string angle_column = "angle_deg";
  BandwidthOptions options;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "bandwidth",
      "Bandwidth (GJB 2426A-2004 5.13, eqs. 32-41) and output delay (5.14, eqs. 42-46) from\n"
      "angular-vibration runs, model G(s) = K/(T s + 1) e^(-Td s), Bw = 1/(2 pi T).\n"
      "GAINS is a CSV with the header 'freq_hz,gain,phase_deg': one row per vibration frequency\n"
      "(Hz, positive, increasing), the gain Gi = Fi/FL (eq. 35) and the phase of the gyro output\n"
      "against the input RATE in deg (negative for a lag).\n"
      "--records RUNS instead: RUNS is a CSV with the header 'freq_hz,file', one record per frequency\n"
      "(paths relative to RUNS). Each record has the columns --time-column (s), --output-column\n"
      "(gyro output) and --angle-column (interferometer angle, --angle-unit); both are sine-fitted at\n"
      "the frequency. Gi = (Fi/Ri)/(FL/RL), Ri the rate amplitude, L the lowest frequency; the phase\n"
      "is the output's against the rate (the angle's phase + 90 deg).\n"
      "At least --minimum-frequencies (default 10, 5.13.3 a) frequencies. A phase beyond +-90 deg at the\n"
      "lowest frequency is a negative scale factor: 180 deg is removed from every phase before the delay\n"
      "fit (polarity -1).\n"
      "Outputs: bandwidth (Hz), delay (s, omega_i = 2 pi f_i), dc_gain, time_constant (s), each with\n"
      "its 1-sigma uncertainty from the fit; polarity (+1 or -1); bode (per frequency: gain, fitted_gain, phase_deg,\n"
      "fitted_phase_deg); with --records also vibration_fits and gain_at_lowest_frequency.");
  command->add_option("GAINS", arguments->gains_file, "CSV freq_hz,gain,phase_deg")->check(CLI::ExistingFile);
  command->add_option("--records", arguments->records_listing, "CSV listing freq_hz,file of raw records")
      ->check(CLI::ExistingFile);
  command->add_option("--time-column", arguments->time_column, "time column of the records (s)")->capture_default_str();
  command->add_option("--output-column", arguments->output_column, "gyro output column of the records")
      ->capture_default_str();
  command->add_option("--angle-column", arguments->angle_column, "interferometer angle column of the records")
      ->capture_default_str();
  command->add_option("--angle-unit", arguments->options.angle_unit, "unit of the angle column")->capture_default_str();
  command->add_option("--output-unit", arguments->options.output_unit, "instrument output unit")->capture_default_str();
  command->add_option("--minimum-frequencies", arguments->options.minimum_frequencies, "fewest frequencies accepted")
      ->capture_default_str();
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    const auto& a = *arguments;
    if (a.gains_file.empty() == a.records_listing.empty()) {
      throw Error("bandwidth: give exactly one of GAINS or --records RUNS");
    }
    BandwidthResult result;
    if (!a.gains_file.empty()) {
      result = bandwidth_and_delay(read_frequency_response(a.gains_file), a.options);
    } else {
      const auto listing = read_file_listing(a.records_listing, "freq_hz");
      const auto records = read_angular_vibration_records(listing, a.time_column, a.output_column, a.angle_column);
      result = bandwidth_and_delay(std::span<const AngularVibrationRecord>(records), a.options);
    }
    print_result(result.to_json(), result.report(), a.json);
    return 0;
  };
}

const bool registered = register_command("bandwidth", setup);

}  // namespace
}  // namespace inertest::cli

// Simulated hand-held IMU tumble for the triad calibration of issue 18 (plan kind "imu_calibration";
// sim/imu_tumble.h): both triads of a MEMS IMU in raw counts, held still in many orientations with
// rotations between them, at the site's gravity. Keys: orientations = 20, still_s = 6,
// sample_rate_hz = 100, offset = 32768 (the counts' mid-scale; 0 for none), quantised = true.
// Writes <name>/tumble.csv (time_s,ax,ay,az,gx,gy,gz). Truth: every parameter of both triads (bias,
// scale factor, non-orthogonality), within 4 of the calibration's reported sigma.
#include <fmt/format.h>

#include "inertest/sim/imu_tumble.h"
#include "sim/generators.h"

namespace inertest::sim {
namespace {

constexpr const char* kAxes = "xyz";

// The truth of one triad's parameters, at the JSON pointers of the calibration's figures.
void add_truth(Lab& lab, const std::string& name, const std::string& triad, const ImuTriadTruth& truth, double offset,
               const std::vector<std::pair<int, int>>& off_diagonal) {
  const std::string basis = "4 sigma: the calibration's covariance s^2 (J^T J)^-1 (Tedaldi et al. 2014)";
  const std::string input = triad == "accelerometer" ? "m/s^2" : "rad/s";
  for (int j = 0; j < 3; ++j) {
    lab.truth.push_back({name, fmt::format("{} bias {}", triad, kAxes[j]), fmt::format("/{}/bias/value/{}", triad, j),
                         truth.bias[j] + offset, "count", 0.0, basis, 0.0, 4.0});
    lab.truth.push_back({name, fmt::format("{} scale factor {}", triad, kAxes[j]),
                         fmt::format("/{}/scale_factor/value/{}", triad, j), truth.scale_factor[j],
                         fmt::format("count/({})", input), 0.0, basis, 0.0, 4.0});
  }
  for (const auto& [i, j] : off_diagonal) {
    lab.truth.push_back({name, fmt::format("{} misalignment {}{}", triad, kAxes[i], kAxes[j]),
                         fmt::format("/{}/misalignment/value/{}/{}", triad, i, j), truth.misalignment[i][j], "rad", 0.0,
                         basis, 0.0, 4.0});
  }
}

}  // namespace

void generate_imu_tumble(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  ImuTumbleOptions options;
  options.orientations = static_cast<std::size_t>(test.number_or("orientations", 20.0));
  options.still_s = test.number_or("still_s", 6.0);
  options.sample_rate_hz = test.number_or("sample_rate_hz", 100.0);
  options.offset = test.number_or("offset", 32768.0);
  options.quantised = test.boolean_or("quantised", true);
  options.gravity_m_s2 = lab.site.gravity_m_s2;
  if (!(options.orientations >= 9)) test.fail_at("orientations", "the calibration needs at least 9 orientations");
  if (!(options.still_s >= 4.0)) test.fail_at("still_s", "hold each orientation for 4 s or more");
  if (!(options.sample_rate_hz >= 20.0)) test.fail_at("sample_rate_hz", "must be 20 Hz or more");
  if (lab.dry_run) return;
  const ImuRecord record = simulate_imu_tumble(options, lab.random(name + "/tumble").seed());
  std::string text = "time_s,ax,ay,az,gx,gy,gz\n";
  for (std::size_t i = 0; i < record.time_s.size(); ++i) {
    text += fmt::format("{:.4f},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", record.time_s[i], record.accelerometer[0][i],
                        record.accelerometer[1][i], record.accelerometer[2][i], record.gyro[0][i], record.gyro[1][i],
                        record.gyro[2][i]);
  }
  const std::string file = name + "/tumble.csv";
  lab.write(file, text);
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"imu_calibration\"\nname = \"{}\"\nfile = \"{}\"\n\n", name, file);
  add_truth(lab, name, "accelerometer", options.accelerometer, options.offset, {{0, 1}, {0, 2}, {1, 2}});
  add_truth(lab, name, "gyro", options.gyro, options.offset, {{0, 1}, {0, 2}, {1, 0}, {1, 2}, {2, 0}, {2, 1}});
  lab.tests.push_back({{"name", name}, {"kind", "imu_tumble"}, {"orientations", options.orientations},
                       {"still_s", options.still_s}, {"sample_rate_hz", options.sample_rate_hz},
                       {"offset", options.offset}, {"quantised", options.quantised}});
}

}  // namespace inertest::sim

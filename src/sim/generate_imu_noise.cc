// Simulated six-axis IMU at rest for the noise analysis of issue 19 (plan kind "allan" with
// columns): a MEMS-grade gyro triad (deg/s) and accelerometer triad (m/s^2), each axis with the
// random drift of IEEE Std 952-1997 Annex C (noise.h) and, on gz, a sinusoid (a vibration seen in
// the record). Keys: hours = 6, sample_rate_hz = 10, sine_amplitude_deg_s = 0.01 and
// sine_frequency_hz = 1.25 (on gz; 0 for none). Writes <name>/imu.csv (time_s,gx,gy,gz,ax,ay,az).
// Truth: N, B and K of every axis, within 4 of the fit's reported sigma. The step asks for the PSD too,
// so the report shows the sinusoid as a periodic component.
#include <fmt/format.h>

#include "inertest/core/units.h"
#include "inertest/sim/imu_noise.h"
#include "sim/generators.h"

namespace inertest::sim {
namespace {

// Per axis: N, B, K in the units the analysis reports them (deg/sqrt(h), deg/h, deg/h/sqrt(h) for
// the gyros; m/s/sqrt(h), ug, m/s/h/sqrt(h) for the accelerometers).
struct AxisTruth {
  const char* name;
  double n, b, k;
};
constexpr AxisTruth kGyros[] = {{"gx", 0.30, 5.0, 10.0}, {"gy", 0.25, 4.0, 8.0}, {"gz", 0.35, 6.0, 12.0}};
constexpr AxisTruth kAccelerometers[] = {{"ax", 0.06, 50.0, 4.0}, {"ay", 0.05, 40.0, 3.0}, {"az", 0.07, 60.0, 5.0}};

}  // namespace

void generate_imu_noise(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const double hours = test.number_or("hours", 6.0);
  const double rate = test.number_or("sample_rate_hz", 10.0);
  const double sine_amplitude = test.number_or("sine_amplitude_deg_s", 0.01);
  const double sine_frequency = test.number_or("sine_frequency_hz", 1.25);
  if (!(hours > 0.0)) test.fail_at("hours", "must be positive");
  if (!(rate > 0.0)) test.fail_at("sample_rate_hz", "must be positive");
  if (!(sine_frequency >= 0.0 && sine_frequency < rate / 2.0)) {
    test.fail_at("sine_frequency_hz", "must lie between 0 and half the sample rate");
  }
  if (lab.dry_run) return;
  std::vector<ImuAxisNoise> axes;
  const auto add = [&](const AxisTruth& t, bool gyro) {
    ImuAxisNoise axis;
    axis.name = t.name;
    axis.unit = gyro ? "deg/s" : "m/s^2";
    axis.noise.angle_random_walk = convert(t.n, gyro ? "deg/sqrt(h)" : "m/s/sqrt(h)", "(" + axis.unit + ")*sqrt(s)");
    axis.noise.bias_instability = convert(t.b, gyro ? "deg/h" : "ug", axis.unit);
    axis.noise.rate_random_walk = convert(t.k, gyro ? "deg/h/sqrt(h)" : "m/s/h/sqrt(h)", "(" + axis.unit + ")/sqrt(s)");
    // Gauss-Markov processes from well below the sample interval: the flicker's PSD is 1/f up to the
    // Nyquist frequency, where the PSD fit reads N.
    axis.noise.flicker_shortest_s = 1.0 / (16.0 * rate);
    axes.push_back(axis);
    const std::string pointer = fmt::format("/channels/{}/noise/", t.name);
    const std::string basis = "4 sigma: the fit's edf-based uncertainty (GJB 2426A eq. 30)";
    const char* n_key = gyro ? "angle_random_walk" : "velocity_random_walk";
    const char* k_key = gyro ? "rate_random_walk" : "acceleration_random_walk";
    lab.truth.push_back({name, fmt::format("{} {}", t.name, gyro ? "angle random walk N" : "velocity random walk N"),
                         pointer + n_key, t.n, gyro ? "deg/sqrt(h)" : "m/s/sqrt(h)", 0.0, basis, 0.0, 4.0});
    lab.truth.push_back({name, fmt::format("{} bias instability B", t.name), pointer + "bias_instability", t.b,
                         gyro ? "deg/h" : "ug", 0.0, basis, 0.0, 4.0});
    lab.truth.push_back({name,
                         fmt::format("{} {}", t.name, gyro ? "rate random walk K" : "acceleration random walk K"),
                         pointer + k_key, t.k, gyro ? "deg/h/sqrt(h)" : "m/s/h/sqrt(h)", 0.0, basis, 0.0, 4.0});
  };
  for (const AxisTruth& t : kGyros) add(t, true);
  for (const AxisTruth& t : kAccelerometers) add(t, false);
  axes[2].sine_amplitude = sine_amplitude;
  axes[2].sine_frequency_hz = sine_frequency;
  const auto samples = lab.samples(hours * 3600.0, rate);
  const auto columns = simulate_imu_noise(axes, rate, samples, lab.random(name + "/imu").seed());
  std::string text = "time_s,gx,gy,gz,ax,ay,az\n";
  for (std::size_t i = 0; i < samples; ++i) {
    text += fmt::format("{:.2f}", static_cast<double>(i) / rate);
    for (const auto& column : columns) text += fmt::format(",{:.9g}", column[i]);
    text += '\n';
  }
  const std::string file = name + "/imu.csv";
  lab.write(file, text);
  lab.plan_steps += fmt::format(
      "[[procedure]]\nkind = \"allan\"\nname = \"{}\"\nfile = \"{}\"\nsample_rate_hz = {}\n"
      "columns = [\"gx\", \"gy\", \"gz\", \"ax\", \"ay\", \"az\"]\ninput_unit = \"deg/s,ax=m/s^2,ay=m/s^2,az=m/s^2\"\n"
      "psd = true\n\n",
      name, file, exact(rate));
  lab.tests.push_back({{"name", name}, {"kind", "imu_noise"}, {"hours", hours}, {"sample_rate_hz", rate},
                       {"sine_amplitude_deg_s", sine_amplitude}, {"sine_frequency_hz", sine_frequency}});
}

}  // namespace inertest::sim

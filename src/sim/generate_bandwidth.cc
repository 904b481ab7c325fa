// Simulated bandwidth and delay test, GJB 2426A-2004 5.13-5.14: the gyro on the angular vibration
// table (IA along its axis), sampled fast, with the table's interferometer angle recorded alongside,
// at each frequency in turn. Test keys:
//   frequencies_hz = [5, 10, 20, 40, 80, 120, 160, 200, 300, 400, 500]
//   rate_amplitude_deg_s = 10   # the table angle amplitude is this over 2πf
//   sample_rate_hz = 5000       # the test station's sampling of the gyro's pulse output
//   cycles = 20, minimum_seconds = 0.5   # each run: whole cycles, at least both of these
// Writes <name>/vib_NN.csv (time_s,output,angle_deg; time at the centre of each counting interval,
// the angle sampled there) and the plan's [[procedure.run]] listing.
//
// Truth: the model's f_c and d. Expected: the fit of eqs. (37)-(46) to the response the test
// station sees, which adds to the gyro's e^(−iωd)/(1 + iω/ωc) the pulse counter's averaging over a
// sample (gain sinc(πf/fs), no phase at the interval's centre) and the model's piecewise-linear input
// between internal steps h (trapezoid gain (ωh/2)·cot(ωh/2)). Tolerance: 4 sigma from the noise of
// the sine fits (ARW and the counter's one-pulse quantisation per sample), carried through the same
// fit by its Jacobian.
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/units.h"
#include "sim/generators.h"

namespace inertest::sim {
namespace {

constexpr unsigned kOversampling = 8;

struct Response {
  std::vector<double> omega;  // rad/s
  std::vector<double> gain;   // output amplitude per rate amplitude (unnormalised)
  std::vector<double> phase;  // rad, against the rate
};

// Eqs. (37)-(41) and (43)-(46), written out here: Gi = gain_i/gain_1; [K², T²] by least squares of
// Gi² = K² − Gi²ωi²T²; Td = Σωi(−Pi − atan(ωiT)) / Σωi².
std::array<double, 2> fit(const Response& r) {
  double s11 = 0, s12 = 0, s22 = 0, b1 = 0, b2 = 0;
  for (std::size_t i = 0; i < r.omega.size(); ++i) {
    const double g2 = std::pow(r.gain[i] / r.gain[0], 2);
    const double a2 = -g2 * r.omega[i] * r.omega[i];
    s11 += 1;
    s12 += a2;
    s22 += a2 * a2;
    b1 += g2;
    b2 += a2 * g2;
  }
  const double det = s11 * s22 - s12 * s12;
  const double t2 = (s11 * b2 - s12 * b1) / det;
  const double t = std::sqrt(t2);
  double num = 0, den = 0;
  for (std::size_t i = 0; i < r.omega.size(); ++i) {
    num += r.omega[i] * (-r.phase[i] - std::atan(r.omega[i] * t));
    den += r.omega[i] * r.omega[i];
  }
  return {1.0 / (2.0 * constants::kPi * t), num / den};
}

}  // namespace

void generate_bandwidth(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const std::vector<double> frequencies = test.optional_numbers("frequencies_hz")
                                              .value_or(std::vector<double>{5, 10, 20, 40, 80, 120, 160, 200, 300, 400, 500});
  const double amplitude = test.number_or("rate_amplitude_deg_s", 10.0);
  const double fs = test.number_or("sample_rate_hz", 5000.0);
  const double cycles = test.number_or("cycles", 20.0);
  const double minimum_seconds = test.number_or("minimum_seconds", 0.5);
  if (frequencies.size() < 10) test.fail_at("frequencies_hz", "GJB 2426A 5.13.3 a) asks for at least 10 frequencies");
  for (std::size_t i = 0; i < frequencies.size(); ++i) {
    if (!(frequencies[i] > 0.0) || (i > 0 && !(frequencies[i] > frequencies[i - 1]))) {
      test.fail_at("frequencies_hz", "must be positive and increase");
    }
    if (!(frequencies[i] < fs / 4.0)) test.fail_at("frequencies_hz", "must stay below a quarter of sample_rate_hz");
  }
  if (!(amplitude > 0.0) || !(cycles >= 1.0) || !(minimum_seconds > 0.0)) {
    test.fail("rate_amplitude_deg_s, cycles and minimum_seconds must be positive");
  }
  if (lab.gyro.bandwidth_hz <= 0.0) test.fail("the gyro has no bandwidth_hz to measure");
  if (lab.dry_run) return;
  GyroParameters gyro = lab.gyro;
  gyro.sample_rate_hz = fs;
  const double dt = 1.0 / fs;
  const double h = dt / kOversampling;
  std::string runs;
  Response expected;
  std::vector<double> sigma_amplitude;  // 1-sigma of the output sine amplitude, deg/s
  // Per-sample output noise: ARW N/√dt plus the counter (difference of two uniform remainders).
  const double sample_noise =
      std::hypot(gyro.noise().angle_random_walk / constants::kDegree / std::sqrt(dt),
                 std::sqrt(2.0 / 12.0) / (std::abs(gyro.scale_factor) * dt));
  for (std::size_t i = 0; i < frequencies.size(); ++i) {
    const double f = frequencies[i];
    const double n_cycles = std::ceil(std::max(cycles, minimum_seconds * f) - 1e-9);
    const auto samples = static_cast<std::size_t>(std::llround(n_cycles / f * fs));
    GyroModel model(gyro, lab.random(fmt::format("{}/{}Hz", name, f)), 3600.0);
    VibrationTable table{f, amplitude * constants::kDegree / (2.0 * constants::kPi * f), model.time_s()};
    const Rig rig = table.rig(lab.site, constant_temperature(gyro.reference_temperature_c));
    const auto pulses = model.record(rig, samples, kOversampling);
    std::string text = fmt::format("# angular vibration '{}' at {} Hz, rate amplitude {} deg/s, {} Hz sampling; "
                                   "angle from the interferometer\ntime_s,output,angle_deg\n",
                                   name, f, amplitude, fs);
    for (std::size_t k = 0; k < pulses.size(); ++k) {
      const double t = (static_cast<double>(k) + 0.5) * dt;
      fmt::format_to(std::back_inserter(text), "{:.7f},{},{:.10g}\n", t, exact(static_cast<double>(pulses[k]) * fs),
                     table.angle(table.start_s + t) / constants::kDegree);
    }
    const std::string file = fmt::format("{}/vib_{:02d}.csv", name, i);
    lab.write(file, text);
    runs += fmt::format("[[procedure.run]]\nfrequency_hz = {}\nfile = \"{}\"\n", exact(f), file);
    // The response the station sees (see the header).
    const double w = 2.0 * constants::kPi * f;
    // Gain 1/√(1 + (ω/ωc)²), unwrapped phase −ω·d − atan(ω/ωc) (eq. 42).
    const double ratio = w / (2.0 * constants::kPi * gyro.bandwidth_hz);
    const double counter = std::sin(w * dt / 2.0) / (w * dt / 2.0);
    const double trapezoid = (w * h / 2.0) / std::tan(w * h / 2.0);
    expected.omega.push_back(w);
    expected.gain.push_back(counter * trapezoid / std::sqrt(1.0 + ratio * ratio));
    expected.phase.push_back(-w * gyro.delay_ms * 1e-3 - std::atan(ratio));
    sigma_amplitude.push_back(sample_noise * std::sqrt(2.0 / static_cast<double>(samples)));
  }
  const std::array<double, 2> predicted = fit(expected);
  // Jacobian of (Bw, Td) in each output amplitude and phase.
  std::array<double, 2> variance{};
  for (std::size_t i = 0; i < frequencies.size(); ++i) {
    const double relative = sigma_amplitude[i] / (amplitude * expected.gain[i]);  // of the gain, and the phase in rad
    for (int which = 0; which < 2; ++which) {
      Response perturbed = expected;
      const double step = 1e-4;
      if (which == 0) {
        perturbed.gain[i] *= 1.0 + step;
      } else {
        perturbed.phase[i] += step;
      }
      const std::array<double, 2> moved = fit(perturbed);
      for (int k = 0; k < 2; ++k) variance[k] += std::pow((moved[k] - predicted[k]) / step * relative, 2);
    }
  }
  const std::string basis = "4 sigma of the sine fits' noise through eqs. (37)-(46); expected includes the counter's "
                            "averaging over a sample";
  lab.truth.push_back({name, "bandwidth", "bandwidth", gyro.bandwidth_hz, "Hz", 4.0 * std::sqrt(variance[0]), basis,
                       predicted[0] - gyro.bandwidth_hz});
  lab.truth.push_back({name, "delay", "delay", gyro.delay_ms * 1e-3, "s", 4.0 * std::sqrt(variance[1]), basis,
                       predicted[1] - gyro.delay_ms * 1e-3});
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"bandwidth\"\nname = \"{}\"\n{}\n", name, runs);
  lab.tests.push_back({{"name", name}, {"kind", "bandwidth"}, {"frequencies_hz", frequencies},
                       {"rate_amplitude_deg_s", amplitude}, {"sample_rate_hz", fs}});
}

}  // namespace inertest::sim

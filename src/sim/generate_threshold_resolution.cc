// Simulated threshold (GJB 2426A-2004 5.10, method 2: dividing head) and resolution (5.11) tests.
// The simulated gyro has no dead zone: every input gives its output, so the 50 % criteria (threshold.h,
// eq. 18) fail only by noise. The truth is then what the walk of 5.10.4 / 5.11.3 gives on the
// noise-free outputs, the smallest tested input of each branch, the largest over the branches; the
// tolerance covers every answer the noise could give: from the first input (walking down) whose
// criterion a 4-sigma error of its mean difference could break, upward.
//
// threshold: IA horizontal on the dividing head (zero mark north), at each reading β the gyro
// senses Ωe·cos φ·cos β (eq. 16). Keys: angles_deg = [0, 30, 60, 80, 85, 88, 89, 90, 91, 92, 95,
// 100, 120, 150, 180], seconds = 60. Writes <name>/positions.csv (angle_deg,output).
//
// resolution: IA up on the rate table at the base rate ±Ω0, then Ω0 + ΔΩj, the base output measured
// again before every increment. Keys: base_rate_deg_s = 1, increments_deg_s = [1e-2, 5e-3, 2e-3,
// 1e-3, 5e-4, 2e-4, 1e-4], seconds = 30. Writes <name>/steps.csv (base_rate,base_output,rate,output).
#include <algorithm>
#include <cmath>
#include <functional>
#include <fmt/format.h>

#include "inertest/core/units.h"
#include "sim/generators.h"

namespace inertest::sim {
namespace {

// The walk of 5.10 / 5.11 on each branch's inputs (any order, positive): from the largest down, the
// candidate is the smallest input with every larger one passing; the answer the largest candidate.
// Noise-free every input passes; `surely_passes` says which still pass under a 4-sigma error.
// Returns {noise-free answer, the largest answer the noise could give}.
template <class SurelyPasses>
std::pair<double, double> noise_bounded_walk(std::vector<std::vector<double>> branches, SurelyPasses surely_passes) {
  double answer = 0.0;
  double highest = 0.0;
  for (auto& inputs : branches) {
    std::sort(inputs.begin(), inputs.end(), std::greater<>());
    if (inputs.empty()) continue;
    answer = std::max(answer, inputs.back());
    double upper = inputs.back();
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      if (!surely_passes(inputs[i])) {
        upper = i == 0 ? inputs[0] : inputs[i - 1];
        break;
      }
    }
    highest = std::max(highest, upper);
  }
  return {answer, highest};
}

}  // namespace

void generate_threshold(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const std::vector<double> angles = test.optional_numbers("angles_deg").value_or(
      std::vector<double>{0, 30, 60, 80, 85, 88, 89, 90, 91, 92, 95, 100, 120, 150, 180});
  const double seconds = test.number_or("seconds", 60.0);
  if (!(seconds > 0.0)) test.fail_at("seconds", "must be positive");
  if (lab.dry_run) return;
  const GyroParameters& gyro = lab.gyro;
  const double fs = gyro.sample_rate_hz;
  GyroModel model(gyro, lab.random(name), 3600.0);
  std::string text = fmt::format("# threshold '{}' (GJB 2426A 5.10, method 2): IA horizontal on the dividing head, "
                                 "mean output over {} s per reading\nangle_deg,output\n",
                                 name, seconds);
  for (const double angle : angles) {
    const double beta = angle * constants::kDegree;
    const Rig rig = static_rig(lab.site, mounting({std::sin(beta), std::cos(beta), 0.0}, {0, 0, 1}),
                               constant_temperature(gyro.reference_temperature_c));
    model.record(rig, static_cast<std::size_t>(std::llround(fs)));
    const auto pulses = model.record(rig, lab.samples(seconds, fs));
    fmt::format_to(std::back_inserter(text), "{},{}\n", exact(angle), exact(mean_output(pulses, fs)));
  }
  lab.write(name + "/positions.csv", text);
  // Eq. (16): Ω_j = Ωe·cos φ·cos β_j. F_j − F0 has σ = √2 times that of a mean; the plan step uses
  // the default criterion, relative to the expected output (IEEE Std 952-1997), which holds for an
  // error e with |e| <= K·|Ω|/2, so it surely holds while 4σ < K·|Ω|/2.
  const double horizontal = lab.site.earth_rate_enu()[1] / constants::kDegree * 3600.0;  // deg/h
  const double sigma = std::sqrt(2.0) * noise_of_mean_deg_s(gyro, seconds) * 3600.0;    // deg/h
  std::vector<double> north, south;
  for (const double angle : angles) {
    const double input = horizontal * std::cos(angle * constants::kDegree);
    if (std::abs(input) < 1e-9 * horizontal) continue;
    (input > 0 ? north : south).push_back(std::abs(input));
  }
  const auto [truth, highest] =
      noise_bounded_walk({north, south}, [&](double input) { return 4.0 * sigma < input / 2.0; });
  lab.truth.push_back({name, "threshold (no dead zone)", "threshold", truth, "deg/h",
                       highest - truth + rounding_tolerance(truth),
                       "the inputs a 4-sigma error could make fail the 50 % criterion; else exact but for rounding"});
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"threshold\"\nname = \"{}\"\nmethod = 2\nfile = \"{}/positions.csv\"\n"
                                "heading_deg = 0\n\n",
                                name, name);
  lab.tests.push_back({{"name", name}, {"kind", "threshold"}, {"method", 2}, {"angles_deg", angles}, {"seconds", seconds}});
}

void generate_resolution(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const double base = test.number_or("base_rate_deg_s", 1.0);
  const std::vector<double> increments = test.optional_numbers("increments_deg_s")
                                             .value_or(std::vector<double>{1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4});
  const double seconds = test.number_or("seconds", 30.0);
  if (!(base > 0.0)) test.fail_at("base_rate_deg_s", "must be positive (it is run both ways)");
  if (!(seconds > 0.0)) test.fail_at("seconds", "must be positive");
  for (const double d : increments) {
    if (!(d > 0.0)) test.fail_at("increments_deg_s", "must be positive");
  }
  if (lab.dry_run) return;
  const GyroParameters& gyro = lab.gyro;
  const double fs = gyro.sample_rate_hz;
  const Matrix3 ia_up = mounting({0, 0, 1}, {1, 0, 0});
  GyroModel model(gyro, lab.random(name), 3600.0);
  auto mean_at = [&](double rate) {
    const Rig rig = lab.rate_table.rig(lab.site, ia_up, rate * constants::kDegree, 0.0, model.time_s(),
                                       constant_temperature(gyro.reference_temperature_c));
    model.record(rig, static_cast<std::size_t>(std::llround(fs)));
    return mean_output(model.record(rig, lab.samples(seconds, fs)), fs);
  };
  std::string text = fmt::format("# resolution '{}' (GJB 2426A 5.11): mean outputs over {} s\n"
                                 "base_rate,base_output,rate,output\n",
                                 name, seconds);
  for (const double sign : {1.0, -1.0}) {
    for (const double d : increments) {
      const double base_output = mean_at(sign * base);
      const double output = mean_at(sign * base + d);
      fmt::format_to(std::back_inserter(text), "{},{},{},{}\n", exact(sign * base), exact(base_output),
                     exact(sign * base + d), exact(output));
    }
  }
  lab.write(name + "/steps.csv", text);
  // Eq. (18) with ΔF̂ = K·ΔΩ fails for |e| > K·|ΔΩ|/2; e, the difference of two means, has σ = √2
  // times that of one.
  const double sigma = std::sqrt(2.0) * noise_of_mean_deg_s(gyro, seconds);  // deg/s
  const auto [truth, highest] =
      noise_bounded_walk({increments, increments}, [&](double increment) { return 4.0 * sigma < increment / 2.0; });
  lab.truth.push_back({name, "resolution (no dead zone)", "resolution", truth * 3600.0, "deg/h",
                       (highest - truth) * 3600.0 + rounding_tolerance(truth * 3600.0), "the increments a 4-sigma error could make fail eq. (18); else exact but for rounding"});
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"resolution\"\nname = \"{}\"\nfile = \"{}/steps.csv\"\n\n", name,
                                name);
  lab.tests.push_back({{"name", name}, {"kind", "resolution"}, {"base_rate_deg_s", base},
                       {"increments_deg_s", increments}, {"seconds", seconds}});
}

}  // namespace inertest::sim

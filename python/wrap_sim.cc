// sim: the virtual lab. The gyro's random drift as an array (IEEE Std 952-1997 Annex C, C.1) and
// simulation plans that write the records, the processing plan and truth.json.
#include <cmath>
#include <nlohmann/json.hpp>

#include "bindings.h"
#include "inertest/sim/noise.h"
#include "inertest/sim/random.h"
#include "inertest/sim/simulation.h"

namespace inertest::python {
namespace {

py::array_t<double> gyro_noise(std::size_t sample_count, double sample_rate_hz, double quantization,
                               double angle_random_walk, double bias_instability, double rate_random_walk,
                               double rate_ramp, double flicker_shortest_s, double flicker_longest_s,
                               std::uint64_t seed) {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw Error("gyro_noise: sample_rate_hz must be positive and finite");
  }
  if (!(flicker_shortest_s > 0.0 && flicker_longest_s >= flicker_shortest_s)) {
    throw Error("gyro_noise: need 0 < flicker_shortest_s <= flicker_longest_s");
  }
  for (const double term : {quantization, angle_random_walk, bias_instability, rate_random_walk, rate_ramp}) {
    if (!(term >= 0.0) || !std::isfinite(term)) throw Error("gyro_noise: noise terms must be finite and >= 0");
  }
  const sim::NoiseParameters parameters{quantization,     angle_random_walk,  bias_instability, rate_random_walk,
                                        rate_ramp,        flicker_shortest_s, flicker_longest_s};
  std::vector<double> rate(sample_count);
  {
    py::gil_scoped_release release;
    sim::NoiseGenerator generator(parameters, 1.0 / sample_rate_hz, sim::Random(seed));
    for (double& sample : rate) sample = generator.next();
  }
  return to_numpy(std::move(rate));
}

Record summary_record(const sim::SimulationSummary& summary) {
  return Record({{"truth", summary.truth}, {"plan_path", summary.plan_path}, {"written_files", summary.written_files}});
}

}  // namespace

void wrap_sim(py::module_& module) {
  using namespace pybind11::literals;
  module.def("gyro_noise", &gyro_noise, "sample_count"_a, "sample_rate_hz"_a, py::kw_only(), "quantization"_a = 0.0,
             "angle_random_walk"_a = 0.0, "bias_instability"_a = 0.0, "rate_random_walk"_a = 0.0, "rate_ramp"_a = 0.0,
             "flicker_shortest_s"_a = 1.0, "flicker_longest_s"_a = 1.0e5, "seed"_a = 1,
             "The simulator's gyro random drift: the mean noise rate (rad/s) over each of sample_count intervals,\n"
             "made so that its Allan deviation is the one IEEE Std 952-1997 Annex C (C.1, eqs. C.2-C.12)\n"
             "ascribes to each term: Q (rad) sqrt(3) Q / tau, N (rad/sqrt(s)) N / sqrt(tau), B (rad/s) 0.664 B,\n"
             "K (rad/s/sqrt(s)) K sqrt(tau / 3), R (rad/s^2) R tau / sqrt(2). Same seed, same samples.");
  module.def(
      "simulate",
      [](const std::filesystem::path& plan_path, const std::filesystem::path& out_dir) {
        sim::SimulationSummary summary;
        {
          py::gil_scoped_release release;
          summary = sim::simulate(plan_path.string(), out_dir.string());
        }
        return summary_record(summary);
      },
      "plan_path"_a, "out_dir"_a,
      "Runs a simulation plan (TOML) through the virtual lab, as `inertest simulate`: writes the records,\n"
      "the processing plan (plan.toml) and truth.json into out_dir. Returns a Record with truth, plan_path\n"
      "and written_files. Raises inertest.Error naming the plan file and line.");
}

}  // namespace inertest::python

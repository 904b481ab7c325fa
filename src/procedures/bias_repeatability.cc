#include "inertest/procedures/bias_repeatability.h"

#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/numerics/statistics.h"

namespace inertest {
namespace {

constexpr std::size_t kRecommendedRuns = 6;  // GJB 2426A 5.12.3.3 d)

}  // namespace

BiasRepeatabilityResult bias_repeatability(std::span<const double> run_biases_deg_h) {
  if (run_biases_deg_h.size() < 2) {
    throw Error(fmt::format("bias repeatability: {} run(s); eq. (21) needs at least 2 (GJB 2426A 5.12.3 asks for "
                            "{} or more)",
                            run_biases_deg_h.size(), kRecommendedRuns));
  }
  for (double b : run_biases_deg_h) {
    if (!std::isfinite(b)) throw Error("bias repeatability: a run's bias is not a finite number");
  }
  BiasRepeatabilityResult result;
  result.run_biases.assign(run_biases_deg_h.begin(), run_biases_deg_h.end());
  result.mean_bias = {mean(run_biases_deg_h), "deg/h", std::nullopt};
  result.bias_repeatability = {sample_standard_deviation(run_biases_deg_h), "deg/h", std::nullopt};  // eq. (21)
  if (run_biases_deg_h.size() < kRecommendedRuns) {
    result.warnings.push_back(fmt::format("{} runs; GJB 2426A 5.12.3.3 d) asks for at least {}",
                                          run_biases_deg_h.size(), kRecommendedRuns));
  }
  return result;
}

}  // namespace inertest

#include "inertest/procedures/bias_repeatability.h"

#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

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

nlohmann::json BiasRepeatabilityResult::to_json() const {
  nlohmann::json runs = nlohmann::json::array();
  for (double b : run_biases) runs.push_back(Figure{b, "deg/h", std::nullopt});
  return {
      {"procedure", "bias_repeatability"},
      {"clause", "GJB 2426A-2004 5.12.3, eq. (21)"},
      {"bias_repeatability", bias_repeatability},
      {"mean_bias", mean_bias},
      {"runs", run_biases.size()},
      {"run_biases", runs},
      {"warnings", warnings},
  };
}

std::string BiasRepeatabilityResult::report() const {
  std::string text = "Bias repeatability (GJB 2426A-2004 5.12.3)\n";
  for (std::size_t i = 0; i < run_biases.size(); ++i) {
    text += fmt::format("  {:<32} {:.9g} deg/h\n", fmt::format("bias of run {}", i + 1), run_biases[i]);
  }
  text += fmt::format("  {:<32} {:.9g} deg/h\n", "mean bias", mean_bias.value);
  text += fmt::format("  {:<32} {:.6g} deg/h\n", "bias repeatability Br", bias_repeatability.value);
  for (const auto& w : warnings) text += "  warning: " + w + "\n";
  return text;
}

}  // namespace inertest

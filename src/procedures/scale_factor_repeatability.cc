#include "inertest/procedures/scale_factor_repeatability.h"

#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/numerics/statistics.h"

namespace inertest {

void ScaleFactorRepeatabilityOptions::validate() const {
  scale_factor.validate();
  if (minimum_runs < 2) throw Error("scale factor repeatability: eq. (12) needs at least 2 runs");
}

void ScaleFactorRepeatabilityOptions::check_run_count(std::size_t runs) const {
  if (runs < minimum_runs) {
    throw Error(fmt::format("scale factor repeatability: {} run(s); GJB 2426A 5.8.4.3 asks for Q >= {} runs", runs,
                            minimum_runs));
  }
}

ScaleFactorRepeatabilityResult scale_factor_repeatability(std::span<const double> scale_factors,
                                                          const std::string& unit,
                                                          const ScaleFactorRepeatabilityOptions& options) {
  options.validate();
  const std::size_t q = scale_factors.size();
  options.check_run_count(q);
  // A run of the other sign is a run reversed (the table turned the other way, the output's sign
  // convention), not scatter: eq. (12) made one such run of six Kr = 1 224 741 ppm, unsaid.
  for (std::size_t i = 1; i < q; ++i) {
    if (!(scale_factors[i] * scale_factors[0] > 0.0)) {
      throw Error(fmt::format("scale factor repeatability: run {} has K = {:.8g} and run 1 K = {:.8g}: a run of "
                              "the other sign (or zero) is reversed (the rates' or the output's sign), not scatter",
                              i + 1, scale_factors[i], scale_factors[0]));
    }
  }
  const double k_mean = mean(scale_factors);
  const double kr = sample_standard_deviation(scale_factors) / std::abs(k_mean);  // eq. (12)

  ScaleFactorRepeatabilityResult result;
  result.scale_factor_repeatability = {kr * 1e6, "ppm", std::nullopt};
  result.mean_scale_factor = {k_mean, unit, std::nullopt};
  for (double k : scale_factors) result.run_scale_factors.push_back({k, unit, std::nullopt});
  if (q < 6) {
    result.warnings.push_back(fmt::format("{} runs; GJB 2426A 5.8.4.3 asks for at least 6", q));
  }
  return result;
}

ScaleFactorRepeatabilityResult scale_factor_repeatability(std::span<const std::vector<ScaleFactorPoint>> runs,
                                                          const ScaleFactorRepeatabilityOptions& options) {
  options.validate();
  std::vector<double> values;
  std::vector<Figure> figures;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    try {
      const ScaleFactorResult run = scale_factor(runs[i], options.scale_factor);
      values.push_back(run.scale_factor.value);
      figures.push_back(run.scale_factor);
    } catch (const Error& e) {
      throw Error(fmt::format("scale factor repeatability: run {}: {}", i + 1, e.message()));
    }
  }
  const std::string unit = options.scale_factor.output_unit + "/(" + options.scale_factor.rate_unit + ")";
  ScaleFactorRepeatabilityResult result = scale_factor_repeatability(values, unit, options);
  result.run_scale_factors = figures;
  return result;
}

}  // namespace inertest

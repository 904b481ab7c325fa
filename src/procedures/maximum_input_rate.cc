#include "inertest/procedures/maximum_input_rate.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"

namespace inertest {
namespace {

// The points of a range: the static runs at the start and the end and every rate with |Ω| <= R.
std::vector<ScaleFactorPoint> points_within(std::span<const ScaleFactorPoint> points, double range) {
  std::vector<ScaleFactorPoint> kept;
  for (const auto& p : points) {
    if (std::abs(p.rate) <= range) kept.push_back(p);
  }
  return kept;
}

// Smallest R with at least two distinct rates on each side of zero (what scale_factor() needs).
double smallest_range(std::span<const ScaleFactorPoint> points) {
  std::vector<double> positive;
  std::vector<double> negative;
  for (const auto& p : points) {
    if (p.rate > 0.0) positive.push_back(p.rate);
    if (p.rate < 0.0) negative.push_back(-p.rate);
  }
  auto second_distinct = [](std::vector<double> values, const char* side) {
    std::sort(values.begin(), values.end());
    values.erase(std::unique(values.begin(), values.end()), values.end());
    if (values.size() < 2) {
      throw Error(fmt::format("maximum input rate: {} distinct {} rate(s); needs at least 2 on each side of zero",
                              values.size(), side));
    }
    return values[1];
  };
  return std::max(second_distinct(positive, "positive"), second_distinct(negative, "negative"));
}

}  // namespace

void MaximumInputRateOptions::validate() const {
  scale_factor.validate();
  if (!std::isfinite(nonlinearity_limit_ppm) || nonlinearity_limit_ppm <= 0.0) {
    throw Error("maximum input rate: the nonlinearity requirement must be a positive number of ppm");
  }
}

MaximumInputRateResult maximum_input_rate(std::span<const ScaleFactorPoint> points,
                                          const MaximumInputRateOptions& options) {
  options.validate();
  // Check the whole set first, so missing static runs etc. get scale_factor()'s own message.
  scale_factor(points, options.scale_factor);
  const double first = smallest_range(points);
  // A range [-R, R] is tested only where both directions reach R (GJB 2426A 5.9 and 5.8.1.3 take
  // the rates in both directions up to the maximum): rates beyond the smaller of the two extremes
  // were tested one way only, and a range reaching them would claim the other way untested.
  double positive_reach = 0.0;
  double negative_reach = 0.0;
  for (const auto& p : points) {
    positive_reach = std::max(positive_reach, p.rate);
    negative_reach = std::max(negative_reach, -p.rate);
  }
  const double reach = std::min(positive_reach, negative_reach);
  std::vector<double> candidates;
  for (const auto& p : points) {
    if (std::abs(p.rate) >= first && std::abs(p.rate) <= reach) candidates.push_back(std::abs(p.rate));
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());

  MaximumInputRateResult result;
  result.rate_unit = options.scale_factor.rate_unit;
  std::optional<std::size_t> last_pass;  // the largest range that meets the requirement
  ScaleFactorResult last_pass_fit;
  for (double range : candidates) {
    const std::vector<ScaleFactorPoint> kept = points_within(points, range);
    const ScaleFactorResult fit = scale_factor(kept, options.scale_factor);  // eqs. (1)-(9)
    const bool meets = fit.nonlinearity.value <= options.nonlinearity_limit_ppm;
    result.ranges.push_back({range, fit.nonlinearity.value, meets});
    if (meets) {
      last_pass = result.ranges.size() - 1;
      last_pass_fit = fit;
    }
  }
  if (!last_pass) {
    throw Error(fmt::format("maximum input rate: the nonlinearity is above the requirement of {} ppm over every range "
                            "(|rate| <= {} {}: {:.6g} ppm); the requirement holds at no tested rate",
                            options.nonlinearity_limit_ppm, candidates.back(), result.rate_unit,
                            result.ranges.back().nonlinearity));
  }
  std::vector<std::string> failing_below;  // smaller ranges that miss the requirement: said, not the figure
  for (std::size_t i = 0; i < *last_pass; ++i) {
    if (!result.ranges[i].meets_requirement) {
      failing_below.push_back(fmt::format("{} {} ({:.3g} ppm)", result.ranges[i].rate, result.rate_unit,
                                          result.ranges[i].nonlinearity));
    }
  }
  if (!failing_below.empty()) {
    result.warnings.push_back(fmt::format(
        "the nonlinearity over the smaller ranges |rate| <= {} is above the requirement; the maximum input rate is "
        "the largest range at which it is met (GJB 2426A 5.9): look at those ranges (a small full scale makes the "
        "output's noise a large nonlinearity in ppm; a range in the middle that fails is the characteristic's own)",
        fmt::join(failing_below, ", ")));
  }
  const auto& chosen = result.ranges[*last_pass];
  result.maximum_input_rate = {chosen.rate, result.rate_unit, std::nullopt};
  result.nonlinearity = {chosen.nonlinearity, "ppm", std::nullopt};
  result.nonlinearity_limit = {options.nonlinearity_limit_ppm, "ppm", std::nullopt};
  result.scale_factor = last_pass_fit.scale_factor;
  if (*last_pass + 1 == result.ranges.size()) {
    result.warnings.push_back(fmt::format("the requirement holds up to the largest tested rate ({} {}); the maximum "
                                          "input rate may be higher",
                                          chosen.rate, result.rate_unit));
  }
  if (positive_reach != negative_reach) {
    result.warnings.push_back(fmt::format(
        "the rates reach {} {} in the positive direction and {} {} in the negative: ranges beyond {} {} were "
        "tested one way only and are left out (GJB 2426A 5.9 tests both directions)",
        positive_reach, result.rate_unit, -negative_reach, result.rate_unit, reach, result.rate_unit));
  }
  return result;
}

}  // namespace inertest

#include "inertest/procedures/resolution.h"

#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "procedures/fifty_percent_criterion.h"

namespace inertest {

void ResolutionOptions::validate() const {
  if (scale_factor == 0.0 || !std::isfinite(scale_factor)) {
    throw Error(fmt::format("resolution: the scale factor K must be a nonzero number (output units per deg/s), got {}",
                            scale_factor));
  }
  if (Unit::parse(rate_unit).dimension() != Unit::parse("rad/s").dimension()) {
    throw Error("resolution: rate unit '" + rate_unit + "' is not an angular rate");
  }
}

ResolutionResult resolution(std::span<const ResolutionStep> steps, const ResolutionOptions& options) {
  options.validate();
  std::vector<criterion::Point> forward;
  std::vector<criterion::Point> reverse;
  for (std::size_t j = 0; j < steps.size(); ++j) {
    const auto& s = steps[j];
    if (s.base_rate == 0.0) {
      throw Error(fmt::format("resolution: step {} has a zero base rate; GJB 2426A 5.11.3 b) turns the table well "
                              "above the threshold",
                              j + 1));
    }
    const double increment = convert(s.rate - s.base_rate, options.rate_unit, "deg/h");
    if (increment == 0.0) throw Error(fmt::format("resolution: step {} has a zero rate increment", j + 1));
    const double expected = options.scale_factor * convert(increment, "deg/h", "deg/s");  // ΔF̂_j = K·ΔΩ_j
    (s.base_rate > 0.0 ? forward : reverse).push_back({increment, expected, s.output - s.base_output, 0.0, false});
  }
  if (forward.empty() || reverse.empty()) {
    throw Error(fmt::format("resolution: {} forward and {} reverse step(s); GJB 2426A 5.11.3 d)-e) tests both "
                            "directions",
                            forward.size(), reverse.size()));
  }
  ResolutionResult result;
  double largest = 0.0;
  for (auto* branch_points : {&forward, &reverse}) {
    const std::string name = branch_points == &forward ? "forward" : "reverse";
    const auto outcome = criterion::search(std::move(*branch_points), criterion::Denominator::kExpected,
                                           "resolution (" + name + ")");
    ResolutionBranch branch;
    branch.name = name;
    branch.candidate_deg_h = std::abs(outcome.points[outcome.candidate].input);
    branch.bounded = outcome.bounded;
    for (const auto& p : outcome.points) {
      branch.points.push_back({p.input, p.expected, p.measured, p.relative_error, p.satisfies});
    }
    if (!branch.bounded) {
      result.warnings.push_back(fmt::format("{}: eq. (18) holds down to the smallest increment tested ({:.6g} deg/h); "
                                            "the resolution there is at most that",
                                            name, branch.candidate_deg_h));
    }
    largest = std::max(largest, branch.candidate_deg_h);
    result.branches.push_back(std::move(branch));
  }
  result.resolution = {largest, "deg/h", std::nullopt};
  return result;
}

nlohmann::json ResolutionResult::to_json() const {
  nlohmann::json branch_json = nlohmann::json::array();
  for (const auto& b : branches) {
    nlohmann::json points_json = nlohmann::json::array();
    for (const auto& p : b.points) {
      points_json.push_back({{"increment", Figure{p.increment_deg_h, "deg/h", std::nullopt}},
                             {"expected_output_increment", p.expected_increment},
                             {"output_increment", p.output_increment},
                             {"relative_error", p.relative_error},
                             {"satisfies", p.satisfies}});
    }
    branch_json.push_back({{"name", b.name},
                           {"candidate", Figure{b.candidate_deg_h, "deg/h", std::nullopt}},
                           {"bounded", b.bounded},
                           {"points", points_json}});
  }
  return {
      {"procedure", "resolution"},
      {"clause", "GJB 2426A-2004 5.11.4, eq. (18)"},
      {"resolution", resolution},
      {"branches", branch_json},
      {"warnings", warnings},
  };
}

std::string ResolutionResult::report() const {
  std::string text = "Resolution (GJB 2426A-2004 5.11)\n";
  for (const auto& b : branches) {
    text += fmt::format("  {:<32} {:.6g} deg/h{}\n", "candidate, " + b.name, b.candidate_deg_h,
                        b.bounded ? "" : " (smallest increment tested)");
  }
  text += fmt::format("  {:<32} {:.6g} deg/h\n", "resolution", resolution.value);
  for (const auto& w : warnings) text += "  warning: " + w + "\n";
  return text;
}

}  // namespace inertest

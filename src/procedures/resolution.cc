#include "inertest/procedures/resolution.h"

#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/io/text_table.h"
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
  result.output_unit = options.output_unit;
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

std::vector<ResolutionStep> read_resolution_steps(const std::string& path) {
  TextTableOptions read;
  read.header = TextTableOptions::Header::kPresent;
  read.columns = {ColumnSelector{"base_rate"}, ColumnSelector{"base_output"}, ColumnSelector{"rate"},
                  ColumnSelector{"output"}};
  const TextTable table = read_text_table(path, read);
  std::vector<ResolutionStep> steps;
  for (std::size_t i = 0; i < table.rows(); ++i) {
    steps.push_back({table.columns[0][i], table.columns[1][i], table.columns[2][i], table.columns[3][i]});
  }
  return steps;
}

}  // namespace inertest

#include "inertest/procedures/threshold.h"

#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/core/units.h"
#include "inertest/numerics/statistics.h"
#include "procedures/fifty_percent_criterion.h"

namespace inertest {
namespace {

constexpr double kSecondsPerHour = 3600.0;
const double kEarthRateDegH = constants::kEarthRate / constants::kDegree * kSecondsPerHour;

// |cos β| below this is the IRA east or west (β = 90° or 270°): no Earth-rate input. cos(90°) in
// doubles is 6e-17, not 0, which would otherwise give an input of ~1e-12 deg/h of either sign.
constexpr double kZeroInputCosine = 1e-9;

struct Sample {
  double input_deg_h;
  double output;  // zero not yet removed
};

// Eq. (14) and the 50 % criterion (threshold.h) on one branch.
ThresholdBranch evaluate_branch(const std::string& name, const std::vector<Sample>& samples, double zero,
                                const ThresholdOptions& options) {
  std::vector<criterion::Point> points;
  for (const auto& s : samples) {
    const double expected = options.scale_factor * s.input_deg_h / kSecondsPerHour;  // eq. (14), K per deg/s
    points.push_back({s.input_deg_h, expected, s.output - zero, 0.0, false});
  }
  const auto denominator = options.criterion_denominator == CriterionDenominator::kMeasured
                               ? criterion::Denominator::kMeasured
                               : criterion::Denominator::kExpected;
  const auto outcome = criterion::search(std::move(points), denominator, "threshold (" + name + " inputs)");
  ThresholdBranch branch;
  branch.name = name;
  branch.candidate_deg_h = std::abs(outcome.points[outcome.candidate].input);
  branch.bounded = outcome.bounded;
  for (const auto& p : outcome.points) {
    branch.points.push_back({p.input, p.expected, p.measured, p.relative_error, p.satisfies});
  }
  return branch;
}

ThresholdResult combine(int method, std::vector<ThresholdBranch> branches, double zero,
                        const ThresholdOptions& options) {
  ThresholdResult result;
  result.method = method;
  result.criterion_denominator = options.criterion_denominator;
  double largest = 0.0;
  for (const auto& b : branches) {
    largest = std::max(largest, b.candidate_deg_h);
    if (!b.bounded) {
      result.warnings.push_back(
          fmt::format("{} branch: the 50 % criterion holds down to the smallest input tested "
                      "({:.6g} deg/h); the threshold there is at most that",
                      b.name, b.candidate_deg_h));
    }
  }
  result.threshold = {largest, "deg/h", std::nullopt};
  result.zero_output = {zero, options.output_unit, std::nullopt};
  result.branches = std::move(branches);
  return result;
}

double zero_from(const std::optional<double>& given, const std::vector<double>& measured, const char* what) {
  if (given) return *given;
  if (measured.empty()) {
    throw Error(fmt::format("threshold: no zero output given and no {} to measure it from", what));
  }
  return mean(measured);
}

}  // namespace

const char* criterion_text(CriterionDenominator denominator) {
  return denominator == CriterionDenominator::kMeasured
             ? "|(F_expected - F)/F| <= 50 %, GJB 2426A-2004 eq. (15) as printed (measured output)"
             : "|(F_expected - F)/F_expected| <= 50 %, IEEE Std 952-1997 (output at least 50 % of the expected), "
               "as GJB 2426A-2004 eq. (18)";
}

std::string_view to_string(CriterionDenominator denominator) {
  return denominator == CriterionDenominator::kMeasured ? "measured" : "expected";
}

CriterionDenominator parse_criterion_denominator(std::string_view text) {
  if (text == "expected") return CriterionDenominator::kExpected;
  if (text == "measured") return CriterionDenominator::kMeasured;
  throw Error(
      fmt::format("threshold: criterion denominator '{}' is neither 'expected' (IEEE Std 952-1997) nor "
                  "'measured' (GJB 2426A-2004 eq. (15) as printed)",
                  text));
}

void ThresholdOptions::validate() const {
  if (scale_factor == 0.0 || !std::isfinite(scale_factor)) {
    throw Error(fmt::format("threshold: the scale factor K must be a nonzero number (output units per deg/s), got {}",
                            scale_factor));
  }
  if (latitude_deg && (!std::isfinite(*latitude_deg) || std::abs(*latitude_deg) > 90.0)) {
    throw Error(fmt::format("threshold: latitude {} deg is not in [-90, 90]", *latitude_deg));
  }
  if (!std::isfinite(heading_deg)) throw Error("threshold: the heading is not a finite number");
  if (zero_output && !std::isfinite(*zero_output)) throw Error("threshold: the zero output is not a finite number");
  if (Unit::parse(rate_unit).dimension() != Unit::parse("rad/s").dimension()) {
    throw Error("threshold: rate unit '" + rate_unit + "' is not an angular rate");
  }
}

double ThresholdOptions::latitude_for(const char* method) const {
  if (!latitude_deg) {
    throw ParameterError("latitude", fmt::format("latitude is needed by {}: its input is the Earth rate's horizontal "
                                                 "component, Omega_e cos(latitude) (GJB 2426A eqs. 16-17)",
                                                 method));
  }
  return *latitude_deg;
}

ThresholdResult threshold_rate_table(std::span<const RateTablePoint> points, const ThresholdOptions& options) {
  options.validate();
  std::vector<Sample> positive;
  std::vector<Sample> negative;
  std::vector<double> static_outputs;
  for (const auto& p : points) {
    const double rate = convert(p.rate, options.rate_unit, "deg/h");
    if (rate > 0.0) {
      positive.push_back({rate, p.output});
    } else if (rate < 0.0) {
      negative.push_back({rate, p.output});
    } else {
      static_outputs.push_back(p.output);
    }
  }
  if (positive.empty() || negative.empty()) {
    throw Error(fmt::format("threshold (method 1): {} positive and {} negative rates; GJB 2426A 5.10.3.1 tests both "
                            "directions",
                            positive.size(), negative.size()));
  }
  const double zero = zero_from(options.zero_output, static_outputs, "zero-rate points");
  std::vector<ThresholdBranch> branches;
  branches.push_back(evaluate_branch("positive", positive, zero, options));
  branches.push_back(evaluate_branch("negative", negative, zero, options));
  return combine(1, std::move(branches), zero, options);
}

ThresholdResult threshold_dividing_head(std::span<const DividingHeadPoint> points, const ThresholdOptions& options) {
  options.validate();
  const double horizontal = kEarthRateDegH * std::cos(options.latitude_for("method 2") * constants::kDegree);
  std::vector<Sample> north;
  std::vector<Sample> south;
  std::vector<double> static_outputs;
  for (const auto& p : points) {
    const double beta = (p.angle_deg + options.heading_deg) * constants::kDegree;
    const double c = std::cos(beta);
    if (std::abs(c) < kZeroInputCosine) {  // IRA east or west: no Earth-rate input
      static_outputs.push_back(p.output);
      continue;
    }
    const Sample s{horizontal * c, p.output};  // eq. (16)
    (c > 0.0 ? north : south).push_back(s);
  }
  if (north.empty() || south.empty()) {
    throw Error(fmt::format("threshold (method 2): {} angle(s) toward north and {} toward south; GJB 2426A 5.10.3.2 "
                            "tests both",
                            north.size(), south.size()));
  }
  const double zero = zero_from(options.zero_output, static_outputs, "east or west positions");
  std::vector<ThresholdBranch> branches;
  branches.push_back(evaluate_branch("toward north", north, zero, options));
  branches.push_back(evaluate_branch("toward south", south, zero, options));
  return combine(2, std::move(branches), zero, options);
}

ThresholdResult threshold_rotating(std::span<const double> time_s, std::span<const double> output,
                                   double table_rate_deg_s, const ThresholdOptions& options) {
  options.validate();
  if (!(std::abs(table_rate_deg_s) > 0.0) || !std::isfinite(table_rate_deg_s)) {
    throw Error(fmt::format("threshold (method 3): the table rate must be nonzero, got {} deg/s", table_rate_deg_s));
  }
  if (time_s.size() != output.size()) throw Error("threshold (method 3): times and outputs differ in length");
  if (output.size() < 4) {
    throw Error(fmt::format("threshold (method 3): {} sample(s); at least 4 are needed", output.size()));
  }
  const double horizontal = kEarthRateDegH * std::cos(options.latitude_for("method 3") * constants::kDegree);
  const double zero = options.zero_output ? *options.zero_output : mean(output);
  // Quadrants of θ = ωt + Φ: [0, 90) positive toward the crossing at 90, (90, 180] negative away
  // from it, [180, 270) negative toward the crossing at 270, (270, 360) positive away from it.
  static constexpr const char* kNames[4] = {"positive before 90 deg", "negative after 90 deg",
                                            "negative before 270 deg", "positive after 270 deg"};
  std::vector<Sample> quadrants[4];
  for (std::size_t j = 0; j < output.size(); ++j) {
    double theta = std::fmod(table_rate_deg_s * time_s[j] + options.heading_deg, 360.0);
    if (theta < 0.0) theta += 360.0;
    const double c = std::cos(theta * constants::kDegree);
    if (std::abs(c) < kZeroInputCosine) continue;  // at a crossing (90° or 270°): no input, in no branch
    const double input = horizontal * c;           // eq. (17)
    const int quadrant = theta < 90.0 ? 0 : theta < 180.0 ? 1 : theta < 270.0 ? 2 : 3;
    quadrants[quadrant].push_back({input, output[j]});
  }
  std::vector<ThresholdBranch> branches;
  for (int q = 0; q < 4; ++q) {
    if (quadrants[q].empty()) {
      throw Error(fmt::format("threshold (method 3): no sample in the branch '{}'; the record must cover one whole "
                              "revolution",
                              kNames[q]));
    }
    branches.push_back(evaluate_branch(kNames[q], quadrants[q], zero, options));
  }
  ThresholdResult result = combine(3, std::move(branches), zero, options);
  const double revolutions = std::abs(table_rate_deg_s) * (time_s.back() - time_s.front()) / 360.0;
  if (!options.zero_output && std::abs(revolutions - std::round(revolutions)) > 0.02) {
    result.warnings.push_back(fmt::format("the record spans {:.3f} revolutions; the zero output (the record's mean) is "
                                          "exact only over whole revolutions",
                                          revolutions));
  }
  return result;
}

}  // namespace inertest

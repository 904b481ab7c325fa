// The 50 % criterion shared by threshold and resolution (GJB 2426A-2004 eqs. 15 and 18), and the
// search the test procedure implies: the input is decreased step by step (5.10.3.1 c, 5.11.3 d);
// the candidate is the smallest input at which the criterion still holds, the first failure
// ending the search (a smaller input that passes again by chance after a failure is not counted).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inertest/core/figure.h"

namespace inertest::criterion {

enum class Denominator {
  kMeasured,  // eq. (15): |(F̄_j − F_j) / F_j|, F_j the measured output
  kExpected,  // eq. (18): |(ΔF̂_j − ΔF_j) / ΔF̂_j|, ΔF̂_j the output the fitted line predicts
};

inline constexpr double kLimit = 0.5;  // 50 %

struct Point {
  double input = 0.0;     // signed input (rate or rate increment), any unit
  double expected = 0.0;  // K·input
  double measured = 0.0;  // measured output (or output increment), zero removed
  double relative_error = 0.0;  // filled by search()
  bool satisfies = false;       // filled by search()
};

struct Outcome {
  std::vector<Point> points;     // sorted by decreasing |input|, with relative_error and satisfies
  std::size_t candidate = 0;     // index in points of the smallest passing input before the first failure
  bool bounded = false;          // true when a smaller input failed (the candidate is bracketed)
};

// Throws Error (naming `what`) when there are no points or the largest input already fails.
Outcome search(std::vector<Point> points, Denominator denominator, const std::string& what);

// The JSON of a procedure's branches (threshold, resolution): per direction its name, candidate
// (deg/h), whether it is bounded, and its points, each made by `point_json`.
template <typename Branch, typename PointJson>
nlohmann::json branches_json(const std::vector<Branch>& branches, PointJson point_json) {
  nlohmann::json rows = nlohmann::json::array();
  for (const Branch& b : branches) {
    nlohmann::json points = nlohmann::json::array();
    for (const auto& p : b.points) points.push_back(point_json(p));
    rows.push_back({{"name", b.name},
                    {"candidate", Figure{b.candidate_deg_h, "deg/h", std::nullopt}},
                    {"bounded", b.bounded},
                    {"points", points}});
  }
  return rows;
}

}  // namespace inertest::criterion

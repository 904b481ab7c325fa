// Test points of a scale-factor run made from known parameters, for the scale-factor series tests.
#pragma once

#include <vector>

#include "inertest/procedures/scale_factor.h"

namespace inertest::testing {

// Static runs at start and end with output `bias`, then ±rates with output K·Ω + bias: eqs. (1)-(6)
// give back exactly K.
inline std::vector<ScaleFactorPoint> linear_run(double k, double bias = 0.25,
                                                const std::vector<double>& rates = {1, 2, 5, 10, 20, 50, 100}) {
  std::vector<ScaleFactorPoint> points = {{0.0, bias}};
  for (double r : rates) {
    points.push_back({r, k * r + bias});
    points.push_back({-r, -k * r + bias});
  }
  points.push_back({0.0, bias});
  return points;
}

}  // namespace inertest::testing

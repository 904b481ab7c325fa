// A downstream program: computes a scale factor through the installed library.
#include <cstdio>
#include <vector>

#include "inertest/procedures/scale_factor.h"

int main() {
  std::vector<inertest::ScaleFactorPoint> points = {{0, 1}, {-2, -3}, {-1, -1}, {1, 3}, {2, 5}, {0, 1}};
  const auto result = inertest::scale_factor(points);
  std::printf("scale factor %g\n", result.scale_factor.value);
  return result.scale_factor.value == 2.0 ? 0 : 1;
}

// The simulator's random numbers: std::mt19937_64 (whose sequence the C++ standard fixes) with
// explicit seeding, and uniform and normal variates computed here rather than by
// std::uniform_real_distribution / std::normal_distribution, whose algorithms are
// implementation-defined. The same seed therefore gives the same numbers on every conforming
// machine and standard library.
#pragma once

#include <cstdint>
#include <random>
#include <string_view>

namespace inertest::sim {

class Random {
 public:
  explicit Random(std::uint64_t seed);

  // An independent stream for one named part of a simulation (e.g. "allan/static"): seeded from
  // the parent seed and the name, so adding a test to a plan does not change the others' records.
  Random stream(std::string_view name) const;

  // Uniform on (0, 1): the top 53 bits of one 64-bit draw, offset by half a step so that 0 never
  // occurs.
  double uniform();
  // Standard normal by Marsaglia's polar method (Marsaglia & Bray 1964): only +, *, / , log and
  // sqrt, no trigonometric functions; the second variate of each pair is kept for the next call.
  double normal();

  std::uint64_t seed() const { return seed_; }

 private:
  std::uint64_t seed_;
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace inertest::sim

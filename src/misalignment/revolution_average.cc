#include "inertest/misalignment/revolution_average.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>

#include "inertest/core/error.h"
#include "inertest/numerics/compensated_sum.h"

namespace inertest {
namespace {

// A count of whole revolutions from a number of turns, forgiving the rounding of a sum of steps
// that should land exactly on a whole turn.
std::size_t whole_turns(double turns) { return static_cast<std::size_t>(std::floor(turns * (1.0 + 1e-9))); }

SourceLocation sample_location(const RecordSource& source, std::size_t sample) {
  const std::size_t line = sample < source.row_lines.size() ? source.row_lines[sample] : 0;
  return {source.file, line, 0};
}

void check_sizes(std::size_t a, std::size_t b, const RecordSource& source, const char* column) {
  if (a != b) {
    throw Error(SourceLocation{source.file, 0, 0},
                fmt::format("whole-revolution mean: {} {} values but {} outputs", a, column, b));
  }
  if (a < 2) {
    throw Error(SourceLocation{source.file, 0, 0},
                fmt::format("whole-revolution mean: the record has {} sample(s); at least 2 are needed", a));
  }
}

RevolutionMean mean_of_first(std::span<const double> output, std::size_t count, std::size_t revolutions) {
  CompensatedSum sum;
  for (std::size_t k = 0; k < count; ++k) sum.add(output[k]);
  return {sum.value() / static_cast<double>(count), revolutions, count};
}

}  // namespace

RevolutionMean whole_revolution_mean_by_angle(std::span<const double> table_angle_deg, std::span<const double> output,
                                              const RecordSource& source) {
  const std::size_t n = table_angle_deg.size();
  check_sizes(n, output.size(), source, "table angle");
  // Unwrapped angle travelled from the first sample, deg; each step taken as the shortest way round.
  std::vector<double> travelled(n + 1, 0.0);
  int direction = 0;
  for (std::size_t k = 1; k < n; ++k) {
    const double step = std::remainder(table_angle_deg[k] - table_angle_deg[k - 1], 360.0);
    if (!std::isfinite(step) || std::abs(step) >= 180.0) {
      throw Error(sample_location(source, k),
                  "whole-revolution mean: the table angle steps by half a turn or more between samples (or is not "
                  "a number); the direction of rotation is ambiguous");
    }
    const int sign = (step > 0.0) - (step < 0.0);
    if (sign != 0 && direction != 0 && sign != direction) {
      throw Error(sample_location(source, k),
                  "whole-revolution mean: the table angle turns back; a record must be at one rate and direction");
    }
    if (sign != 0) direction = sign;
    travelled[k] = travelled[k - 1] + step;
  }
  // The last sample covers one mean step beyond its angle.
  travelled[n] = travelled[n - 1] + travelled[n - 1] / static_cast<double>(n - 1);
  const double total = std::abs(travelled[n]);
  const std::size_t revolutions = whole_turns(total / 360.0);
  if (revolutions == 0) {
    throw Error(SourceLocation{source.file, 0, 0},
                fmt::format("whole-revolution mean: the table turns {:.6g} deg in the record, less than one "
                            "revolution; the Earth-rate terms would not average out",
                            total));
  }
  // The sample boundary nearest the end of the last whole revolution.
  const double target = 360.0 * static_cast<double>(revolutions);
  std::size_t count = 1;
  for (std::size_t k = 1; k <= n; ++k) {
    if (std::abs(std::abs(travelled[k]) - target) < std::abs(std::abs(travelled[count]) - target)) count = k;
  }
  return mean_of_first(output, count, revolutions);
}

RevolutionMean whole_revolution_mean_by_time(std::span<const double> time_s, std::span<const double> output,
                                             double rate_dps, const RecordSource& source) {
  const std::size_t n = time_s.size();
  check_sizes(n, output.size(), source, "time");
  if (rate_dps == 0.0 || !std::isfinite(rate_dps)) {
    throw Error(
        SourceLocation{source.file, 0, 0},
        fmt::format("whole-revolution mean: the table rate must be finite and nonzero, got {} deg/s", rate_dps));
  }
  for (std::size_t k = 1; k < n; ++k) {
    if (!(time_s[k] > time_s[k - 1])) {
      throw Error(sample_location(source, k), "whole-revolution mean: the time stamps do not increase");
    }
  }
  const double interval = (time_s[n - 1] - time_s[0]) / static_cast<double>(n - 1);  // Δt
  const double duration = interval * static_cast<double>(n);                         // T = N·Δt
  const double period = 360.0 / std::abs(rate_dps);                                  // s per revolution
  const std::size_t revolutions = whole_turns(duration / period);                    // floor(T·|ω|/360)
  if (revolutions == 0) {
    throw Error(SourceLocation{source.file, 0, 0},
                fmt::format("whole-revolution mean: the record lasts {:.6g} s, less than one revolution ({:.6g} s "
                            "at {} deg/s); the Earth-rate terms would not average out",
                            duration, period, rate_dps));
  }
  const auto count = static_cast<std::size_t>(std::llround(static_cast<double>(revolutions) * period / interval));
  return mean_of_first(output, std::min(std::max<std::size_t>(count, 1), n), revolutions);
}

}  // namespace inertest

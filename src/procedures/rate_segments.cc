#include "inertest/procedures/rate_segments.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/numerics/compensated_sum.h"

namespace inertest {
namespace {

double mean_of(std::span<const double> values) {
  CompensatedSum sum;
  for (double v : values) sum.add(v);
  return sum.value() / static_cast<double>(values.size());
}

void require_finite(std::span<const double> values, const char* what) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) throw Error(fmt::format("{}: sample {} is not finite", what, i + 1));
  }
}

}  // namespace

void RecordTiming::validate() const {
  if (!std::isfinite(sample_rate_hz) || sample_rate_hz <= 0.0) {
    throw Error("record: the sample rate must be positive (Hz)");
  }
  if (!std::isfinite(settling_time_s) || settling_time_s < 0.0) {
    throw Error("record: the settling time must be zero or positive (s)");
  }
}

std::size_t RecordTiming::settling_samples() const {
  return static_cast<std::size_t>(std::ceil(settling_time_s * sample_rate_hz - 1e-9));
}

double record_mean(std::span<const double> output, const RecordTiming& timing) {
  timing.validate();
  require_finite(output, "record");
  const std::size_t skip = timing.settling_samples();
  if (skip >= output.size()) {
    throw Error(fmt::format("record: the settling time of {} s ({} samples) is not shorter than the record "
                            "({} samples at {} Hz)",
                            timing.settling_time_s, skip, output.size(), timing.sample_rate_hz));
  }
  return mean_of(output.subspan(skip));  // eq. (1)
}

void RateSegmentOptions::validate() const {
  timing.validate();
  if (!std::isfinite(rate_tolerance) || rate_tolerance < 0.0) throw Error("rate segments: the rate tolerance must be >= 0");
  if (!(minimum_segment_s > timing.settling_time_s)) {
    throw Error(fmt::format("rate segments: the minimum segment duration ({} s) must exceed the settling time ({} s)",
                            minimum_segment_s, timing.settling_time_s));
  }
}

std::vector<RateSegment> segment_by_rate(std::span<const double> table_rate, std::span<const double> output,
                                         const RateSegmentOptions& options) {
  options.validate();
  if (table_rate.size() != output.size()) {
    throw Error(fmt::format("rate segments: {} table rates but {} outputs", table_rate.size(), output.size()));
  }
  require_finite(table_rate, "rate segments: table rate");
  require_finite(output, "rate segments: output");
  const std::size_t skip = options.timing.settling_samples();
  const auto minimum_samples =
      static_cast<std::size_t>(std::ceil(options.minimum_segment_s * options.timing.sample_rate_hz - 1e-9));

  // A sample belongs to the segment while it lies within the tolerance of the mean of the segment's
  // samples so far; the segment ends where kPersistence samples in a row (fewer at the record's end)
  // lie outside it: the table rate changed. A lone sample outside is a glitch of the measured rate,
  // left out of the segment's means (kept in them, a dropout to 0 in a 300 deg/s plateau moved K by
  // 0.15 %). Against the segment's first sample, noise within the tolerance cut each plateau
  // wherever it swung the other way (24 test points became 56).
  constexpr std::size_t kPersistence = 3;
  constexpr double kRatesOfTolerance = 2.5;
  const std::size_t count = table_rate.size();
  std::vector<RateSegment> segments;
  std::size_t begin = 0;
  while (begin < count) {
    CompensatedSum rate_sum;
    rate_sum.add(table_rate[begin]);
    std::size_t in_mean = 1;
    std::vector<std::size_t> glitches;
    std::size_t end = begin + 1;
    while (end < count) {
      const double running_mean = rate_sum.value() / static_cast<double>(in_mean);
      const auto outside = [&](std::size_t i) { return !(std::abs(table_rate[i] - running_mean) <= options.rate_tolerance); };
      if (outside(end)) {
        bool persists = true;
        for (std::size_t i = end + 1; i < std::min(count, end + kPersistence) && persists; ++i) persists = outside(i);
        if (persists) break;
        glitches.push_back(end);
      } else {
        rate_sum.add(table_rate[end]);
        ++in_mean;
      }
      ++end;
    }
    const std::size_t first_used = begin + skip;
    // One pass over the segment's samples but the glitches (all of them lie inside it): the table
    // rate over its two halves, and the means over the samples after the settling time.
    // A piece of a slow ramp stays within the tolerance of its running mean for about 2 tol / (its
    // acceleration), long enough to pass for a test point: its table rate moves by about tol across
    // it, where a plateau's halves agree to its noise / sqrt(n).
    const std::size_t kept = end - begin - glitches.size();
    const std::size_t first_count = (kept + 1) / 2;
    std::array<CompensatedSum, 2> halves;
    CompensatedSum rate_used;
    CompensatedSum output_used;
    std::size_t used = 0;
    if (end - begin >= minimum_samples) {
      auto glitch = glitches.begin();
      for (std::size_t i = begin, k = 0; i < end; ++i) {
        if (glitch != glitches.end() && *glitch == i) {
          ++glitch;
          continue;
        }
        halves[k++ < first_count ? 0 : 1].add(table_rate[i]);
        if (i < first_used) continue;
        rate_used.add(table_rate[i]);
        output_used.add(output[i]);
        ++used;
      }
    }
    const bool ramp = kept >= 2 && std::abs(halves[1].value() / static_cast<double>(kept - first_count) -
                                            halves[0].value() / static_cast<double>(first_count)) >
                                       0.5 * options.rate_tolerance;
    if (used > 0 && !ramp) {
      RateSegment segment;
      segment.first_sample = begin;
      segment.first_used = first_used;
      segment.end_sample = end;
      const double rate = rate_used.value() / static_cast<double>(used);
      segment.rate = std::abs(rate) <= options.rate_tolerance ? 0.0 : rate;
      segment.mean_output = output_used.value() / static_cast<double>(used);  // eq. (1)
      segments.push_back(segment);
    }
    begin = end;
  }
  if (segments.empty()) {
    throw Error(fmt::format("rate segments: no constant-rate segment of at least {} s ({} samples) in a record of {} "
                            "samples (is the rate tolerance below the table-rate column's noise?)",
                            options.minimum_segment_s, minimum_samples, table_rate.size()));
  }
  // A test rate within a few tolerances of zero says that a smaller one may have been taken for a
  // static run: rates of +-0.001 deg/s at the tolerance 0.001 joined the static runs, moved F̄s by
  // half the output at 0.001 deg/s, F0 by 1000 sigma, and left two test points out, silently.
  for (const RateSegment& segment : segments) {
    if (segment.rate != 0.0 && std::abs(segment.rate) < kRatesOfTolerance * options.rate_tolerance) {
      throw Error(fmt::format("rate segments: the test rate {:.6g} lies within {} rate tolerances ({:g}) of zero: a "
                              "smaller test rate may have been taken for a static run; give a rate tolerance below "
                              "the smallest test rate / {} (samples {} to {})",
                              segment.rate, kRatesOfTolerance, options.rate_tolerance, kRatesOfTolerance,
                              segment.first_sample + 1, segment.end_sample));
    }
  }
  return segments;
}

std::vector<ScaleFactorPoint> scale_factor_points(std::span<const RateSegment> segments) {
  std::vector<ScaleFactorPoint> points;
  points.reserve(segments.size());
  for (const auto& segment : segments) points.push_back({segment.rate, segment.mean_output});
  return points;
}

}  // namespace inertest

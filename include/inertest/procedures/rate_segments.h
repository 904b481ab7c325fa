// Raw records of the scale-factor test (GJB 2426A-2004 5.8.1.3-5.8.1.4) turned into the test
// points that scale_factor() takes.
//
// A lab has either a record per test point (the gyro output while the table turns at one rate) or
// one long record with a table-rate column. The mean of a record after its settling time is F̄j of
// eq. (1) (5.8.1.3 b: "the data before the start-up time are removed, then the mean is taken").
// A long record is cut into constant-rate segments; the settling time after each change of rate is
// dropped, segments shorter than a minimum duration (ramps between rates, glitches) are skipped,
// and each remaining segment becomes one ScaleFactorPoint in test order. Zero-rate segments at the
// start and the end are the static runs of 5.8.1.3 d).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "inertest/procedures/scale_factor.h"

namespace inertest {

struct RecordTiming {
  double sample_rate_hz = 0.0;   // samples per second of the record
  double settling_time_s = 0.0;  // dropped at the start of a record / after each change of rate

  // Throws Error unless the sample rate is positive and the settling time non-negative.
  void validate() const;
  // Number of samples dropped for the settling time (rounded up).
  std::size_t settling_samples() const;
};

// F̄j of eq. (1): the mean of the record after the settling time. Throws Error when the settling
// time leaves no sample (the window is longer than the record) or a sample is not finite.
double record_mean(std::span<const double> output, const RecordTiming& timing);

struct RateSegmentOptions {
  RecordTiming timing;
  // A segment shorter than this (before the settling time is dropped) is a transition, skipped.
  // Must exceed the settling time.
  double minimum_segment_s = 1.0;
  // Table rates within this of the mean rate of the segment so far belong to it (it ends where 3
  // samples in a row lie outside: a lone one is a glitch of the measured rate); a
  // segment whose mean rate lies within it of zero is a static run (rate exactly 0). In the rate
  // column's unit.
  double rate_tolerance = 1e-3;

  void validate() const;
};

struct RateSegment {
  double rate = 0.0;             // mean table rate over the samples used (0 for a static run)
  double mean_output = 0.0;      // F̄j, eq. (1)
  std::size_t first_sample = 0;  // 0-based index where the constant rate begins
  std::size_t first_used = 0;    // first sample after the settling time
  std::size_t end_sample = 0;    // one past the last sample of the segment
};

// Cuts a record into constant-rate segments in test order. Throws Error when the columns differ
// in length, a value is not finite, no segment is long enough, or a test rate lies within 2.5 rate
// tolerances of zero (a smaller one may have joined a static run).
std::vector<RateSegment> segment_by_rate(std::span<const double> table_rate, std::span<const double> output,
                                         const RateSegmentOptions& options);

// The segments as scale-factor test points, in test order.
std::vector<ScaleFactorPoint> scale_factor_points(std::span<const RateSegment> segments);

}  // namespace inertest

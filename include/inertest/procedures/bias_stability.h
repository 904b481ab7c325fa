// Bias stability: GJB 2426A-2004 5.12.2, eq. (20); IEEE Std 952-1997 clause 13 (A.11.3).
//
//   Bs = (1/K) · [ Σ (F_i − F̄)² / (n − 1) ]^½                                            (20)
//
// where F_i are the outputs "after averaging into the sampling interval": the means of consecutive,
// non-overlapping whole windows of the smoothing time (1 s, 10 s and 100 s are what labs quote).
// A partial window at the end of the record is dropped. The functions here work in the record's
// own output unit; bias.h scales by 1/K into deg/h.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace inertest {

// Number of samples in `seconds` at `sample_rate_hz`. Throws Error when the rate or the time is not
// positive, or when the time is not a whole number of sample intervals (to 1e-6 of an interval).
std::size_t samples_in_window(double seconds, double sample_rate_hz);

struct StabilityAtSmoothing {
  double smoothing_s = 0.0;
  std::size_t windows = 0;   // n of eq. (20): the whole windows in the record
  double stability = 0.0;    // standard deviation (n − 1) of the window means, output unit
  std::vector<double> means;  // F_i: the window means themselves, output unit, in record order
};

// Eq. (20) without the 1/K factor. Throws Error for a non-positive rate or smoothing time, a
// window longer than the record, or fewer than two whole windows.
StabilityAtSmoothing output_stability(std::span<const double> output, double sample_rate_hz, double smoothing_s);

}  // namespace inertest

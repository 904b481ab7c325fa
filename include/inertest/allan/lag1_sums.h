// Running sums for the lag-1 autocorrelation of a series that arrives one value at a time, and the
// averaged-frequency series of one averaging factor with its first and second differences, as the
// noise identification of NIST SP 1065 (2008) 5.6 needs them (noise_identification.h). The Allan
// engine fills one AveragedFrequencySeries per averaging factor while it streams the record, so the
// identification never holds the averaged series.
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include "inertest/numerics/compensated_sum.h"

namespace inertest {

// Fewest non-overlapping averages for the lag-1 autocorrelation method (Riley & Greenhall 2004;
// Stable32 uses the B1 ratio below it, noise_identification.h).
inline constexpr std::size_t kLag1MinimumAverages = 30;

// Sums of the series w_1 .. w_n: each value is stored relative to w_1 (the autocorrelation and the
// variance do not depend on a shift, and the shifted values keep the sums of squares small). The
// engine adds one value per sample at m = 1: plain partial sums over kFoldEvery values are folded
// into compensated totals, which keeps the cost at three additions per value and the rounding at
// that of kFoldEvery terms (1e-12 relative), far inside what the identification needs.
class Lag1Sums {
 public:
  void add(double w) {
    if (count_ == 0) shift_ = w;
    const double value = w - shift_;
    partial_.products += previous_ * value;  // previous_ is 0 before the first value
    partial_.sum += value;
    partial_.squares += value * value;
    previous_ = value;
    if (++count_ % kFoldEvery == 0) fold();
  }
  // add() of values[0 .. n) in order (the same sums), with the running sums in registers.
  void add_all(const double* values, std::size_t n);
  std::size_t count() const { return count_; }
  // r1 = sum_{t=1}^{n-1} (w_t - w̄)(w_{t+1} - w̄) / sum_{t=1}^{n} (w_t - w̄)^2, the lag-1
  // autocorrelation of W. J. Riley and C. A. Greenhall, "Power law noise identification using the
  // lag 1 autocorrelation", Proc. 18th EFTF (2004), eq. (2). NaN for n < 2 or a constant series.
  double autocorrelation() const;
  // The sample variance sum (w_t - w̄)^2 / (n - 1); NaN for n < 2.
  double sample_variance() const;
  // The mean square sum w_t^2 / n (about zero, not about the mean); NaN for n = 0.
  double mean_square() const;

 private:
  static constexpr std::size_t kFoldEvery = 4096;
  void fold();
  struct Totals {
    double sum = 0.0;       // sum (w - w_1)
    double squares = 0.0;   // sum (w - w_1)^2
    double products = 0.0;  // sum (w_t - w_1)(w_{t+1} - w_1)
  };
  Totals totals() const;  // folded and partial sums together

  std::size_t count_ = 0;
  double shift_ = 0.0;     // w_1
  double previous_ = 0.0;  // w_n - w_1
  Totals partial_;         // since the last fold
  CompensatedSum sum_;
  CompensatedSum squares_;
  CompensatedSum products_;
};

// The non-overlapping averages of the rate over m samples, ȳ_j, j = 1 .. min(floor(N/m),
// kMaximumAverages), and their first and second differences (series(d), d = 0, 1, 2), fed in order
// with add(); averages past kMaximumAverages are ignored. Bounded prefix: the lag-1
// autocorrelation of 2^16 averages scatters by 1/sqrt(2^16) = 0.004, far below the 0.25 that
// separates two noise types (NIST SP 1065 5.6: delta = r1 / (1 + r1) rounded to a quarter), and the
// B1 ratio is only used below 30 averages; summing every average of the small factors cost each
// channel of an IMU record about a fifth of its engine time for nothing.
class AveragedFrequencySeries {
 public:
  static constexpr std::size_t kOrders = 3;
  static constexpr std::size_t kMaximumAverages = std::size_t{1} << 16;
  void add(double average) {
    if (series_[0].count() >= kMaximumAverages) return;
    double value = average;
    for (std::size_t d = 0; d < kOrders; ++d) {
      const bool has_previous = series_[d].count() > 0;
      const double previous = last_[d];
      series_[d].add(value);
      last_[d] = value;
      if (!has_previous) break;
      value -= previous;
    }
  }
  // add() of each value in order (the same sums), on a copy whose state stays in registers: the
  // engine feeds the averages of a run at once.
  void add_all(std::span<const double> averages);
  // d = 0: the averages; d = 1, 2: their d-th differences.
  const Lag1Sums& series(std::size_t d) const { return series_.at(d); }

 private:
  std::array<Lag1Sums, kOrders> series_;
  std::array<double, kOrders> last_{};
};

}  // namespace inertest

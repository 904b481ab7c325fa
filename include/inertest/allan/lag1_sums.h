// Running sums for the lag-1 autocorrelation of a series that arrives one value at a time, and the
// averaged-frequency series of one averaging factor with its first and second differences, as the
// noise identification of NIST SP 1065 (2008) 5.6 needs them (noise_identification.h). The Allan
// engine fills one AveragedFrequencySeries per averaging factor while it streams the record, so the
// identification never holds the averaged series.
#pragma once

#include <array>
#include <cstddef>

#include "inertest/numerics/compensated_sum.h"

namespace inertest {

// Sums of the series w_1 .. w_n: each value is stored relative to w_1 (the autocorrelation and the
// variance do not depend on a shift, and the shifted values keep the sums of squares small).
class Lag1Sums {
 public:
  void add(double w);
  std::size_t count() const { return count_; }
  // r1 = sum_{t=1}^{n-1} (w_t - w̄)(w_{t+1} - w̄) / sum_{t=1}^{n} (w_t - w̄)^2, the lag-1
  // autocorrelation of W. J. Riley and C. A. Greenhall, "Power law noise identification using the
  // lag 1 autocorrelation", Proc. 18th EFTF (2004), eq. (2). NaN for n < 2 or a constant series.
  double autocorrelation() const;
  // The sample variance sum (w_t - w̄)^2 / (n - 1); NaN for n < 2.
  double sample_variance() const;

 private:
  double squares_about_mean() const;

  std::size_t count_ = 0;
  double shift_ = 0.0;     // w_1
  double previous_ = 0.0;  // w_n - w_1
  CompensatedSum sum_;       // sum (w - w_1)
  CompensatedSum squares_;   // sum (w - w_1)^2
  CompensatedSum products_;  // sum (w_t - w_1)(w_{t+1} - w_1)
};

// The non-overlapping averages of the rate over m samples, ȳ_j, j = 1 .. floor(N/m), and their
// first and second differences (series(d), d = 0, 1, 2), fed in order with add().
class AveragedFrequencySeries {
 public:
  static constexpr std::size_t kOrders = 3;
  void add(double average);
  // d = 0: the averages; d = 1, 2: their d-th differences.
  const Lag1Sums& series(std::size_t d) const { return series_.at(d); }

 private:
  std::array<Lag1Sums, kOrders> series_;
  std::array<double, kOrders> last_{};
};

}  // namespace inertest

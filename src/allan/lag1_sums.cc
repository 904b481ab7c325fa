#include "inertest/allan/lag1_sums.h"

#include <limits>

namespace inertest {

void Lag1Sums::add(double w) {
  if (count_ == 0) shift_ = w;
  const double value = w - shift_;
  if (count_ > 0) products_.add(previous_ * value);
  sum_.add(value);
  squares_.add(value * value);
  previous_ = value;
  ++count_;
}

double Lag1Sums::squares_about_mean() const {
  const double sum = sum_.value();
  return squares_.value() - sum * sum / static_cast<double>(count_);
}

double Lag1Sums::autocorrelation() const {
  if (count_ < 2) return std::numeric_limits<double>::quiet_NaN();
  const double n = static_cast<double>(count_);
  const double mean = sum_.value() / n;
  const double denominator = squares_about_mean();
  if (!(denominator > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  // sum_{t<n} (w_t - w̄)(w_{t+1} - w̄) = sum w_t w_{t+1} - w̄ (2 sum w - w_1 - w_n) + (n - 1) w̄^2,
  // with w_1 = 0 after the shift.
  const double numerator = products_.value() - mean * (2.0 * sum_.value() - previous_) + (n - 1.0) * mean * mean;
  return numerator / denominator;
}

double Lag1Sums::sample_variance() const {
  if (count_ < 2) return std::numeric_limits<double>::quiet_NaN();
  return squares_about_mean() / static_cast<double>(count_ - 1);
}

void AveragedFrequencySeries::add(double average) {
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

}  // namespace inertest

#include "inertest/allan/lag1_sums.h"

#include <limits>

namespace inertest {

void Lag1Sums::fold() {
  sum_.add(partial_.sum);
  squares_.add(partial_.squares);
  products_.add(partial_.products);
  partial_ = {};
}

Lag1Sums::Totals Lag1Sums::totals() const {
  CompensatedSum sum = sum_;
  CompensatedSum squares = squares_;
  CompensatedSum products = products_;
  sum.add(partial_.sum);
  squares.add(partial_.squares);
  products.add(partial_.products);
  return {sum.value(), squares.value(), products.value()};
}

double Lag1Sums::autocorrelation() const {
  if (count_ < 2) return std::numeric_limits<double>::quiet_NaN();
  const Totals t = totals();
  const double n = static_cast<double>(count_);
  const double mean = t.sum / n;
  const double denominator = t.squares - t.sum * mean;  // sum (w_t - w̄)^2
  if (!(denominator > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  // sum_{t<n} (w_t - w̄)(w_{t+1} - w̄) = sum w_t w_{t+1} - w̄ (2 sum w - w_1 - w_n) + (n - 1) w̄^2,
  // with w_1 = 0 after the shift.
  const double numerator = t.products - mean * (2.0 * t.sum - previous_) + (n - 1.0) * mean * mean;
  return numerator / denominator;
}

double Lag1Sums::sample_variance() const {
  if (count_ < 2) return std::numeric_limits<double>::quiet_NaN();
  const Totals t = totals();
  return (t.squares - t.sum * t.sum / static_cast<double>(count_)) / static_cast<double>(count_ - 1);
}

double Lag1Sums::mean_square() const {
  if (count_ == 0) return std::numeric_limits<double>::quiet_NaN();
  const Totals t = totals();
  const double n = static_cast<double>(count_);
  // sum w^2 = sum (v + w_1)^2 with v = w - w_1.
  return (t.squares + shift_ * (2.0 * t.sum + n * shift_)) / n;
}

}  // namespace inertest

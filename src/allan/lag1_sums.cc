#include "inertest/allan/lag1_sums.h"

#include <algorithm>
#include <limits>

namespace inertest {

void Lag1Sums::fold() {
  sum_.add(partial_.sum);
  squares_.add(partial_.squares);
  products_.add(partial_.products);
  partial_ = {};
}

void Lag1Sums::add_all(const double* values, std::size_t n) {
  std::size_t i = 0;
  if (count_ == 0 && n > 0) add(values[i++]);  // the first value sets the shift
  const double shift = shift_;
  double previous = previous_;
  Totals partial = partial_;
  std::size_t count = count_;
  for (; i < n; ++i) {
    const double value = values[i] - shift;
    partial.products += previous * value;
    partial.sum += value;
    partial.squares += value * value;
    previous = value;
    if (++count % kFoldEvery == 0) {
      sum_.add(partial.sum);
      squares_.add(partial.squares);
      products_.add(partial.products);
      partial = {};
    }
  }
  previous_ = previous;
  partial_ = partial;
  count_ = count;
}

// Order by order over a batch: each series gets the values add() would give it, in the same order
// (order d + 1 the differences of the values of order d after its first).
void AveragedFrequencySeries::add_all(std::span<const double> averages) {
  constexpr std::size_t kBatch = 512;
  double values[kBatch];
  double next[kBatch];
  while (!averages.empty() && series_[0].count() < kMaximumAverages) {
    std::size_t n = std::min({averages.size(), kBatch, kMaximumAverages - series_[0].count()});
    std::copy_n(averages.begin(), n, values);
    averages = averages.subspan(n);
    for (std::size_t d = 0; d < kOrders && n > 0; ++d) {
      double last = last_[d];
      bool has_previous = series_[d].count() > 0;
      std::size_t count = 0;
      for (std::size_t i = 0; i < n; ++i) {
        if (has_previous) next[count++] = values[i] - last;
        last = values[i];
        has_previous = true;
      }
      series_[d].add_all(values, n);
      last_[d] = last;
      std::copy_n(next, count, values);
      n = count;
    }
  }
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

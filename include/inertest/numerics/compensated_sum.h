// Compensated (Neumaier / Kahan-Babuska) summation: the rounding error of a sum of n terms stays at
// a few ulp of the result instead of growing with n. Used wherever records of 10^9 samples are
// summed. Neumaier, ZAMM 54 (1974) 39-51.
#pragma once

#include <cmath>
#include <span>

namespace inertest {

class CompensatedSum {
 public:
  void add(double x) {
    const double t = sum_ + x;
    if (std::abs(sum_) >= std::abs(x)) {
      compensation_ += (sum_ - t) + x;
    } else {
      compensation_ += (x - t) + sum_;
    }
    sum_ = t;
  }
  CompensatedSum& operator+=(double x) {
    add(x);
    return *this;
  }
  // Merges a partial sum computed elsewhere (e.g. by another thread).
  void merge(const CompensatedSum& other) {
    add(other.sum_);
    add(other.compensation_);
  }
  double value() const { return sum_ + compensation_; }

 private:
  double sum_ = 0.0;
  double compensation_ = 0.0;
};

inline double compensated_sum(std::span<const double> values) {
  CompensatedSum sum;
  for (double v : values) sum.add(v);
  return sum.value();
}

}  // namespace inertest

#include "inertest/procedures/bias_stability.h"

#include <cmath>
#include <fmt/format.h>
#include <vector>

#include "inertest/core/error.h"
#include "inertest/numerics/statistics.h"

namespace inertest {

std::size_t samples_in_window(double seconds, double sample_rate_hz) {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw Error(fmt::format("the sample rate must be positive, got {} Hz", sample_rate_hz));
  }
  if (!(seconds > 0.0) || !std::isfinite(seconds)) {
    throw Error(fmt::format("a smoothing time must be positive, got {} s", seconds));
  }
  const double exact = seconds * sample_rate_hz;
  const double whole = std::round(exact);
  if (whole < 1.0 || std::abs(exact - whole) > 1e-6 * std::max(1.0, whole)) {
    // The rate a record's jittered stamps give (9.999385 Hz) is no nominal one: the hint says how to state it.
    throw Error(fmt::format("a smoothing time of {} s is not a whole number of samples at {} Hz ({:.6g} samples; "
                            "a rate read from jittered time stamps is no nominal one: give it, --rate)",
                            seconds, sample_rate_hz, exact));
  }
  return static_cast<std::size_t>(whole);
}

StabilityAtSmoothing output_stability(std::span<const double> output, double sample_rate_hz, double smoothing_s) {
  const std::size_t window = samples_in_window(smoothing_s, sample_rate_hz);
  if (window > output.size()) {
    throw Error(fmt::format("bias stability: a smoothing time of {} s ({} samples) is longer than the record "
                            "({} samples, {} s)",
                            smoothing_s, window, output.size(), static_cast<double>(output.size()) / sample_rate_hz));
  }
  // The means about the first sample (eq. 20's deviation does not depend on it), then the offset
  // back for the smoothed record: an output offset of 1e9 with noise of 1e-3 lost 1.4e-3 of Bs(100 s).
  const double reference = output.front();
  std::vector<double> means = window_means(output, window, reference);
  if (means.size() < 2) {
    throw Error(fmt::format("bias stability: the record holds {} whole window(s) of {} s; eq. (20) needs at least 2",
                            means.size(), smoothing_s));
  }
  const double stability = sample_standard_deviation(means);
  for (double& m : means) m += reference;
  return {smoothing_s, means.size(), stability, std::move(means)};
}

}  // namespace inertest

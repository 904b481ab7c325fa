#include "inertest/procedures/turn_on_time.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/numerics/compensated_sum.h"

namespace inertest {
namespace {

constexpr double kSecondsPerHour = 3600.0;

struct Series {
  std::vector<double> time_s;
  std::vector<double> output;
};

// The window (k·s, (k+1)·s] of a sample stamped t: a sample's stamp is the end of the interval
// whose mean it is (sample i of a rate at (i + 1)/HZ), so the sample stamped s is the first
// window's last, not the second's first (that put the first second's last sample, still settling,
// into the next window and added a whole window to the time). A stamp within 1e-9 s of a window's
// end is that window's (decimal rates: 3 x 0.1 s is 0.30000000000000004 s); a stamp at power-on
// (t = 0), the first window's.
double window_of(double t, double smoothing_s) {
  return std::max(0.0, std::ceil((t - 1e-9) / smoothing_s) - 1.0);
}

// Means over windows (k·s, (k+1)·s] of time since power-on, each stamped at (k+1)·s. A window
// holding no sample is skipped, and so is a last window the record ends inside (its stamp would lie
// after the record: a turn-on time longer than the test); the record ends half a sample interval
// after its last sample. A record shorter than one window is an Error.
Series smooth(const PowerOnRun& run, double smoothing_s, const char* what) {
  const std::size_t n = run.time_s.size();
  const double record_end = run.time_s.back() + 0.5 * (run.time_s.back() - run.time_s.front()) / static_cast<double>(n - 1);
  Series series;
  std::size_t i = 0;
  while (i < n) {
    const double window = window_of(run.time_s[i], smoothing_s);
    if ((window + 1.0) * smoothing_s > record_end) break;
    CompensatedSum sum;
    std::size_t count = 0;
    while (i < n && window_of(run.time_s[i], smoothing_s) == window) {
      sum.add(run.output[i]);
      ++count;
      ++i;
    }
    series.time_s.push_back((window + 1.0) * smoothing_s);
    series.output.push_back(sum.value() / static_cast<double>(count));
  }
  if (series.time_s.empty()) {
    throw Error(fmt::format("{}: run '{}' ends at {} s, inside its first smoothing window of {} s", what, run.name,
                            run.time_s.back(), smoothing_s));
  }
  return series;
}

}  // namespace

void TurnOnTimeOptions::validate() const {
  if (scale_factor == 0.0 || !std::isfinite(scale_factor)) {
    throw Error(fmt::format("turn-on time: the scale factor K must be a nonzero number (output units per deg/s), got {}",
                            scale_factor));
  }
  if (!(rate_band >= 0.0) || !(rest_band_deg_h >= 0.0)) throw Error("turn-on time: a band must not be negative");
  if (!(smoothing_s >= 0.0) || !std::isfinite(smoothing_s)) {
    throw Error(fmt::format("turn-on time: the smoothing time must be zero or positive, got {} s", smoothing_s));
  }
  if (!std::isfinite(zero_output)) throw Error("turn-on time: the zero output is not a finite number");
  if (earth_rate) earth_rate->validate();
}

TurnOnTimeResult turn_on_time(std::span<const PowerOnRun> runs, const TurnOnTimeOptions& options) {
  options.validate();
  const char* what = options.warm_up ? "warm-up time" : "turn-on time";
  if (runs.empty()) throw Error(fmt::format("{}: no power-on runs", what));
  const double earth_deg_s = options.earth_rate ? earth_rate_on_axis(*options.earth_rate) / constants::kDegree : 0.0;
  // The Earth rate is removed at rate only (below): asked for with every run at rest it would do
  // nothing, and a run that then never settles would not say why.
  const auto is_at_rest = [](const PowerOnRun& run) { return run.input_rate_deg_s == 0.0; };
  if (options.earth_rate && std::all_of(runs.begin(), runs.end(), is_at_rest)) {
    throw Error(fmt::format("{}: the Earth rate is removed from runs at rate only (GJB 2426A 5.5.4: at rest the IRA "
                            "points east or west, where it has none), and every run is at rest: leave out "
                            "remove_earth_rate (at rest in another direction, the zero output given holds it)",
                            what));
  }
  TurnOnTimeResult result;
  double longest = -1.0;
  for (const auto& run : runs) {
    if (run.time_s.size() != run.output.size()) {
      throw Error(fmt::format("{}: run '{}' has {} times and {} outputs", what, run.name, run.time_s.size(),
                              run.output.size()));
    }
    if (run.output.size() < 2) {
      throw Error(fmt::format("{}: run '{}' holds {} sample(s); at least 2 are needed", what, run.name,
                              run.output.size()));
    }
    for (std::size_t i = 1; i < run.time_s.size(); ++i) {
      if (!(run.time_s[i] > run.time_s[i - 1])) {
        throw Error(fmt::format("{}: run '{}': the time of sample {} does not increase", what, run.name, i + 1));
      }
    }
    // The times count from power-on (5.5.4): a first stamp later than the record lasts is a clock's
    // (an epoch, a time of day), and the figure would be that clock's reading (1.7e9 s).
    const double span = run.time_s.back() - run.time_s.front();
    if (run.time_s.front() > span) {
      throw Error(fmt::format("{}: run '{}': its times start at {:.9g} s, later than the record lasts ({:.6g} s): "
                              "they must count seconds from power-on (GJB 2426A 5.5.4; subtract the power-on time)",
                              what, run.name, run.time_s.front(), span));
    }
    const bool at_rest = run.input_rate_deg_s == 0.0;
    if (at_rest && options.rest_band_deg_h == 0.0) {
      throw Error(fmt::format("{}: run '{}' is at rest but no rest band (required bias, deg/h) was given", what, run.name));
    }
    if (!at_rest && options.rate_band == 0.0) {
      throw Error(fmt::format("{}: run '{}' is at rate but no rate band (relative rate error) was given", what, run.name));
    }
    const Series series =
        options.smoothing_s > 0.0 ? smooth(run, options.smoothing_s, what) : Series{run.time_s, run.output};
    // GJB 2426A 5.5.4: the rate test removes the Earth rate and the calibrated zero from the output,
    // the position test (at rest, IRA east or west) the calibrated zero only.
    const double removed_deg_s = at_rest ? 0.0 : earth_deg_s;
    auto within = [&](double output) {
      const double indicated = (output - options.zero_output) / options.scale_factor - removed_deg_s;  // deg/s
      if (at_rest) return std::abs(indicated) * kSecondsPerHour <= options.rest_band_deg_h;
      return std::abs(indicated - run.input_rate_deg_s) <= options.rate_band * std::abs(run.input_rate_deg_s);
    };
    // The time after which the output stays within the band: walk back from the end.
    std::size_t first = series.output.size();
    while (first > 0 && within(series.output[first - 1])) --first;
    if (first == series.output.size()) {
      throw Error(fmt::format("{}: run '{}' is outside the band at its last sample (t = {} s): it never settles within "
                              "the record",
                              what, run.name, series.time_s.back()));
    }
    const double time = series.time_s[first];
    result.runs.push_back({run.name, run.input_rate_deg_s, Figure{time, "s", std::nullopt}});
    // Noise alone crosses the band now and then: a time in the record's last tenth is more likely
    // its last crossing than the gyro's settling (3593 s of a 3600 s run that settled at 210 s).
    if (series.time_s.back() - time < 0.1 * (series.time_s.back() - series.time_s.front())) {
      result.warnings.push_back(fmt::format(
          "run '{}' enters the band for good only at {:.6g} s, {:.3g} s before its record ends: a time so late may be "
          "the last crossing of the band by the output's noise{}",
          run.name, time, series.time_s.back() - time,
          options.smoothing_s > 0.0 ? " (a longer smoothing_s averages more of it)" : "; smoothing_s averages it"));
    }
    if (time > longest) {
      longest = time;
      result.longest_run = run.name;
    }
  }
  result.time = {longest, "s", std::nullopt};
  return result;
}

}  // namespace inertest

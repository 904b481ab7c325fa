// Mean output of a rate-table record over whole revolutions, so that the Earth-rate terms of the
// gyro misalignment model (ωe·cosφ·sin(ωt), ωe·cosφ·cos(ωt), misalignment paper) average to zero.
//
// Samples are taken as equally spaced; sample k stands for the interval from its angle (or time) to
// the next. Whole revolutions are cut from the start of the record.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace inertest {

// Where the record came from, for error locations (both optional).
struct RecordSource {
  std::string file;
  std::span<const std::size_t> row_lines;  // 1-based line of each sample
};

struct RevolutionMean {
  double mean = 0.0;             // mean output over the whole revolutions
  std::size_t revolutions = 0;   // number of whole revolutions averaged
  std::size_t samples_used = 0;  // samples 0 .. samples_used-1
};

// From the table angle column (deg, may wrap at 360 or -180/180): the angle is unwrapped, the
// number of whole revolutions is n = floor(|θ_last − θ_0| / 360), and the mean is over the samples
// before the one whose unwrapped angle is nearest θ_0 ± n·360. Throws Error when the record has
// fewer than two samples, the table turns both ways, steps by half a turn or more between samples,
// or makes no whole revolution.
RevolutionMean whole_revolution_mean_by_angle(std::span<const double> table_angle_deg, std::span<const double> output,
                                              const RecordSource& source = {});

// From the time column (s) and the table rate (deg/s): a record of duration T = N·Δt (Δt from the
// first and last time stamps) holds n = floor(T·|ω|/360) whole revolutions; the mean is over the
// samples whose time from the start is below n·360/|ω| (to the nearest sample). Throws Error when
// the rate is zero, the time stamps do not increase, or the record is shorter than one revolution.
RevolutionMean whole_revolution_mean_by_time(std::span<const double> time_s, std::span<const double> output,
                                             double rate_dps, const RecordSource& source = {});

}  // namespace inertest

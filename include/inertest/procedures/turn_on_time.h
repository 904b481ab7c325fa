// Turn-on time and warm-up time: GJB 2426A-2004 5.5.4 and 5.6.4 (5.6 computes as 5.5); IEEE Std
// 952-1997 clause 13 (A.4, A.5).
//
// From records that start at power-on, at rate (the table turning at Ω, the IRA along its axis) and
// at rest, each run's time is the time from power-on until the indicated rate stays within the
// required band for the rest of the record:
//   indicated rate ω(t) = (F(t) − F0) / K − Ωe·(IRA)        (calibrated zero F0 and Earth rate removed)
//   at rate:  |ω(t) − Ω| <= rate_band · |Ω|                  (the rate error requirement, relative)
//   at rest:  |ω(t)|     <= rest_band                        (the required bias band, deg/h)
// The turn-on (warm-up) time is the largest over the runs (5.5.4). F0 is the output at zero input
// rate (Earth rate excluded). Optional smoothing averages the samples into windows of
// smoothing_s from power-on, each stamped at its end, before the band is tested.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/procedures/earth_rate.h"

namespace inertest {

struct PowerOnRun {
  std::string name;               // e.g. the file name, for messages and the report
  double input_rate_deg_s = 0.0;  // Ω, the table rate about the IRA; 0 for a run at rest
  std::vector<double> time_s;     // time since power-on of each sample, increasing
  std::vector<double> output;     // instrument output
};

struct TurnOnTimeOptions {
  bool warm_up = false;          // report as warm-up time (5.6) instead of turn-on time (5.5)
  double scale_factor = 0.0;     // K, output units per deg/s
  double zero_output = 0.0;      // F0, the calibrated zero, output units
  double rate_band = 0.0;        // at rate: allowed |ω − Ω| / |Ω| (e.g. 1e-3); needed when a run is at rate
  double rest_band_deg_h = 0.0;  // at rest: allowed |ω| in deg/h; needed when a run is at rest
  double smoothing_s = 0.0;      // 0: test every sample
  std::optional<AxisOrientation> earth_rate;  // Earth rate along the IRA to remove (absent: none)
  // The instrument's output unit: a record that stores a rate unit must store this one (an
  // instrument whose output is in deg/s), not a rate K would divide again.
  std::string output_unit = "1";

  void validate() const;  // throws Error for a zero scale factor, a negative band or smoothing time
};

struct PowerOnRunResult {
  std::string name;
  double input_rate_deg_s = 0.0;
  Figure time;  // s
};

struct TurnOnTimeResult {
  Figure time;  // the largest over the runs, s
  std::string longest_run;
  std::vector<PowerOnRunResult> runs;
  // A run that enters the band for good only in the last tenth of its record: its time may be
  // that of the noise of single samples (smoothing_s averages it).
  std::vector<std::string> warnings;
};

// Throws Error for no runs, a run with fewer than 2 samples, times that do not increase, a missing
// band for a kind of run present, or a run whose output is outside the band at its last sample
// (it never settles within the record).
TurnOnTimeResult turn_on_time(std::span<const PowerOnRun> runs, const TurnOnTimeOptions& options);

// The procedures' specs (src/procedures/turn_on_time_spec.cc): CLI, plan step, JSON and text of turn-on
// time (warm_up false) or warm-up time (true), each run a timed record numbered by its input rate.
ProcedureSpec power_on_time_spec(bool warm_up);
ProcedureSpec turn_on_time_spec();
ProcedureSpec warm_up_time_spec();

}  // namespace inertest

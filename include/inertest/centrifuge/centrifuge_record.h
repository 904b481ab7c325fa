// Reading a centrifuge test record, one of two kinds told apart by the header row:
//   harmonic amplitudes: accel_g,beta_deg,k0,k1c,k1s,k2c,k2s          (one row per run, deg/h)
//   raw samples:         accel_g,beta_deg,gamma_deg,output            (one row per sample, deg/h)
// Either may add a column omega_rad_s (the main-axis rate; otherwise sqrt(accel_g * g / R0)).
// Columns may come in any order; a missing or unknown column is an Error at the header line.
// Sample rows with equal (accel_g, beta_deg) form one run, in order of appearance.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "inertest/centrifuge/drift_calibration.h"

namespace inertest::centrifuge {

struct CentrifugeRecord {
  enum class Kind { kHarmonics, kSamples };
  Kind kind = Kind::kHarmonics;
  std::vector<CentrifugeRun> harmonic_runs;      // kind == kHarmonics
  std::vector<CentrifugeSampleRun> sample_runs;  // kind == kSamples

  // The runs as harmonic amplitudes: as read, or by harmonic analysis of the samples.
  std::vector<CentrifugeRun> runs() const;
};

CentrifugeRecord read_centrifuge_record(const std::string& path);

// The same on text in memory; `source` names it in messages.
CentrifugeRecord parse_centrifuge_record(std::string_view text, const std::string& source);

}  // namespace inertest::centrifuge

// Bandwidth and output delay from angular-vibration runs: GJB 2426A-2004 5.13 (eqs. 32-41) and
// 5.14 (eqs. 42-46).
//
// Model (eq. 42): G(s) = K_D / (T·s + 1) · e^(−Td·s), T = 1/(2π·Bw) (eq. 38).
// Bandwidth: with the gains Gi at ωi = 2π·fi (rad/s), the linearised least squares of eq. (37)
// Gi² = K² − Gi²·ωi²·T² gives B = [K², T²] (eq. 40) and Bw = 1/(2π·√T²) (eq. 41).
// Delay: with Pi the phase of the output against the input RATE (negative for a lag),
// −Pi − atan(ωi·T) = ωi·Td (eq. 44), so Td = (ΩΩᵀ)⁻¹Ω[−Pi − atan(ωi·T)] (eqs. 45-46).
// Polarity: a gyro of negative scale factor has every Pi offset by π. When the phase at the lowest
// frequency lies beyond ±90° the output's polarity is taken as negative and π is removed from
// every phase before eqs. (43)-(46) (result.polarity = −1).
//
// Two inputs: a table of gains and phases (one per frequency), or raw records per frequency with
// the gyro output and the interferometer angle, reduced by a sine fit at the vibration frequency.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/numerics/sine_fit.h"

namespace inertest {

struct FrequencyResponsePoint {
  double frequency_hz = 0.0;  // fi > 0, strictly increasing over the points
  double gain = 0.0;          // Gi (eq. 35), > 0
  double phase_rad = 0.0;     // Pi: phase of the output against the input rate, negative for a lag
};

// One angular-vibration run (5.13.3 b): the gyro output and the interferometer angle, sampled
// together, while the table vibrates at frequency_hz.
struct AngularVibrationRecord {
  double frequency_hz = 0.0;
  std::vector<double> time_s;
  std::vector<double> output;  // gyro output, instrument unit
  std::vector<double> angle;   // interferometer angle, BandwidthOptions::angle_unit
  std::string source;          // names the run in messages (e.g. its file)
};

struct BandwidthOptions {
  // GJB 2426A 5.13.3 a): at least 10 frequencies, log spaced. Fewer is an Error; lowering this
  // (to no less than 3, the fit's two parameters plus one degree of freedom) adds a warning.
  std::size_t minimum_frequencies = 10;
  std::string angle_unit = "deg";   // unit of AngularVibrationRecord::angle
  std::string output_unit = "1";    // instrument output unit, for the gain of the records

  void validate() const;
};

// What the sine fits of one raw record gave (5.13.4, eqs. 32-34).
struct VibrationFit {
  double frequency_hz = 0.0;
  SineFit output;         // F_i, Φ_F (eq. 34)
  SineFit angle;          // Aθm, Φθ (eq. 32)
  double rate_amplitude;  // Aθm·ω, angle unit per s (eq. 33)
};

struct BodePoint {
  double frequency_hz = 0.0;
  double gain = 0.0;               // measured Gi
  double fitted_gain = 0.0;        // K/√(1 + ωi²T²)
  double phase_deg = 0.0;          // measured Pi (unwrapped, the polarity's 180° removed)
  double fitted_phase_deg = 0.0;   // −atan(ωi·T) − ωi·Td
};

struct BandwidthResult {
  Figure bandwidth;        // Bw, Hz, eqs. (37)-(41)
  Figure delay;            // Td, s, eqs. (43)-(46)
  Figure dc_gain;          // K = √B(1), the gain's unit (1 for Gi = Fi/FL)
  Figure time_constant;    // T = √B(2), s (eq. 38)
  Figure gain_fit_residual_rms;   // rms of the residuals of eq. (37), gain² unit
  Figure phase_fit_residual_rms;  // rms of the residuals of eq. (44), rad → deg
  int polarity = 1;        // sign of the output against the input rate: −1 when π was removed from the phases
  std::vector<BodePoint> bode;
  std::vector<VibrationFit> vibration_fits;  // raw-record input only
  std::string output_unit;                   // raw-record input only
  std::string angle_unit;
  std::vector<std::string> warnings;
};

// From a table of gains and phases. Throws Error when fewer than minimum_frequencies points are
// given, a frequency is not positive or not above the one before, a gain is not positive, or the
// fit gives T² <= 0 or K² <= 0 (no bandwidth can be determined).
BandwidthResult bandwidth_and_delay(std::span<const FrequencyResponsePoint> points, const BandwidthOptions& options = {});

// From raw records, one per frequency in increasing order. Each record's output and angle are fitted
// by a sine at its frequency; Fi is the output amplitude and Pi = Φ_F − (Φθ + π/2) the phase of the
// output against the input rate (eqs. 33, 43). Gi = (Fi/Ri)/(FL/RL) with Ri = Aθm,i·ωi the rate
// amplitude: eq. (35) Gi = Fi/FL assumes the same rate amplitude at every frequency; dividing by Ri
// keeps the gain right when the amplitude is changed between frequencies (5.13.3 a allows it).
BandwidthResult bandwidth_and_delay(std::span<const AngularVibrationRecord> records, const BandwidthOptions& options = {});

// The frequency response of the raw records (the sine fits and the points above), without the fit.
std::vector<VibrationFit> fit_vibration_records(std::span<const AngularVibrationRecord> records,
                                                const BandwidthOptions& options);

// The procedure's one description (src/procedures/bandwidth_spec.cc): a table of gains (file) or a
// raw record per frequency ([[procedure.run]], --records RUNS.csv with the header freq_hz,file).
ProcedureSpec bandwidth_spec();

}  // namespace inertest

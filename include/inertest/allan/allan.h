// Allan variance analysis of a rate record (GJB 2426A-2004 5.12.5.4.2, IEEE Std 952-1997 Annex C,
// NIST SP 1065): the deviations ADEV, OADEV, MDEV, HDEV, OHDEV and TOTDEV on a tau grid, each with
// chi-squared confidence bounds, and the noise terms Q, N, B, K, R by the fit of GJB eq. (30) and by
// the slope read-off.
//
// The mean of the record is removed (computed with compensated sums in a first pass) before the
// rate is integrated, so that a constant bias changes no deviation. Noise types for the edf: at each
// tau and for each estimator, the dominant power-law noise identified as Stable32 does (lag-1
// autocorrelation, else B1 ratio and R(n); noise_identification.h), from sums the engine gathers
// while it streams the record; the edf follow from it (confidence.h), and the eq. (30) fit is
// weighted by them.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "inertest/allan/allan_engine.h"
#include "inertest/allan/confidence.h"
#include "inertest/allan/noise_identification.h"
#include "inertest/allan/noise_terms.h"
#include "inertest/allan/power_spectral_density.h"
#include "inertest/io/rate_record.h"
#include "inertest/core/figure.h"
#include "inertest/core/progress.h"

namespace inertest {

// The clause of GJB 2426A-2004 the analysis implements (the JSON's "clause"; "procedure" is
// "allan_variance").
inline constexpr const char* kAllanClause = "GJB 2426A-2004 5.12.5.4.2";

struct AllanOptions {
  double sample_rate_hz = 0.0;
  std::string input_unit = "deg/h";  // unit of the samples (after `scale`)
  std::string taus = "octave";       // a TauGrid specification
  EstimatorSet estimators = EstimatorSet::all();
  // Each sample is multiplied by this before the analysis (e.g. 3600 / scale factor, to turn raw
  // instrument output into deg/h). Applied to the results, which are linear in it.
  double scale = 1.0;
  double confidence = kOneSigmaConfidence;
  std::size_t worker_count = 2;
  // Most phase values the engine's ring may hold; larger averaging factors are computed in a second
  // pass that re-reads the record (AllanEngine). 0: for files, from the record so that the peak
  // memory stays within 1.5 times its raw binary size; in memory, no limit.
  std::size_t ring_capacity_limit = 0;
  // The taus of the fit of GJB eq. (30); empty: chosen automatically (noise_terms.h).
  std::optional<FitRange> fit_range;
  // The power spectral density beside the Allan variance (issue 19; power_spectral_density.h): its
  // noise terms, compared with the fit's (a warning when they disagree), and its periodic
  // components. Its sample rate is sample_rate_hz. A streamed record is then read into memory.
  std::optional<WelchOptions> psd;

  // Throws Error saying what is wrong (rate, unit, tau grid, estimators, scale, confidence).
  void validate() const;
};

struct DeviationCurve {
  std::string unit;
  std::vector<double> values;
  std::vector<double> lower;  // confidence bounds (AllanOptions::confidence)
  std::vector<double> upper;
  std::vector<double> edf;
  std::vector<std::size_t> terms;  // number of terms of the sum
  std::vector<NoiseType> noise_types;  // per tau, identified for this estimator, used for its edf
  std::vector<NoiseIdentificationMethod> noise_methods;  // per tau, how noise_types was found
};

struct AllanResult {
  std::size_t sample_count = 0;
  double sample_rate_hz = 0.0;
  std::string input_unit;
  std::string tau_grid;
  double confidence = 0.0;
  Figure mean;
  std::vector<double> tau_s;
  std::vector<std::size_t> averaging_factors;
  std::vector<NoiseType> noise_types;  // per tau, identified for the Allan variance (as for ADEV)
  std::map<Estimator, DeviationCurve> curves;
  std::optional<NoiseTerms> noise;
  std::optional<SlopeReadOff> slopes;
  std::optional<PowerSpectralDensity> psd;  // when AllanOptions::psd asked for it
  std::vector<std::string> warnings;

  nlohmann::json to_json() const;
  std::string report() const;
};

// On samples in memory. Throws Error for too few samples, a bad tau grid or bad options.
AllanResult allan_variance(std::span<const double> rate, const AllanOptions& options);
// The same, computed in the samples' own memory: they are overwritten (with the integrated phase)
// instead of copied into the engine's ring. For a record read only to be analysed.
AllanResult allan_variance_in_place(std::span<double> rate, const AllanOptions& options);

// Streams a binary file once (the engine integrates about the mean of the first chunk and the mean
// comes from the phase total); text is parsed once into memory and analysed there in place (8 N
// bytes, no ring). Memory for a binary record is the engine's ring buffer, at most 8 (N + 1) bytes
// plus a few MB, and for raw binary records and records of named
// channels (.mat, HDF5, TDMS) at most 1.5 times the file size: the largest averaging factors are
// then computed in a second, partial pass that re-reads the file. A record that stores its sample rate (HDF5
// sample_rate_hz, TDMS wf_increment) must agree with options.sample_rate_hz, else an Error naming both.
AllanResult allan_variance_of_file(const RateRecordSource& source, const AllanOptions& options,
                                   const ProgressCallback& progress = {});

}  // namespace inertest

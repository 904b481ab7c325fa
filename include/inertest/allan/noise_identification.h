// Identification of the dominant power-law noise S_y(f) ~ f^alpha at each averaging time, for the
// edf of the confidence bounds (NIST SP 1065 (2008) 5.6), as Stable32 does it:
//   - with at least 30 non-overlapping averages of the rate at the averaging time, the lag-1
//     autocorrelation method of W. J. Riley and C. A. Greenhall, "Power law noise identification
//     using the lag 1 autocorrelation", Proc. 18th EFTF (2004) (lag1_alpha);
//   - with fewer, the B1 ratio of D. A. Howe, R. L. Beard, C. A. Greenhall, W. J. Riley, "A total
//     estimator of the Hadamard function used for GPS operations", Proc. 32nd PTTI (2000), Tables 3
//     and 4, with the ratio R(n) = MVAR/AVAR (D. B. Sullivan et al. (eds.), NIST Technical Note 1337
//     (1990), Table A-6) to tell white from flicker PM for MDEV (b1_mu, identify_power_law_noise).
// The records are rates (frequency data): the averages are those of the rate, ȳ_j, and alpha is the
// estimate p of Riley & Greenhall (their p + 2 is for phase data). The integer alpha is clamped to
// the five types of NoiseType (+2 .. -2).
#pragma once

#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "inertest/allan/allan_engine.h"
#include "inertest/allan/confidence.h"
#include "inertest/allan/lag1_sums.h"

namespace inertest {

enum class NoiseIdentificationMethod {
  kLag1Autocorrelation,
  kB1Ratio,
  kB1RatioAndRn,
  kShorterTau,
  kNotIdentified
};

// "lag1_autocorrelation", "b1_ratio", "b1_ratio_and_rn", "shorter_tau" (that of the next shorter
// averaging time), "not_identified" (white FM assumed).
std::string_view noise_identification_method_name(NoiseIdentificationMethod method);

struct NoiseIdentification {
  NoiseType type = NoiseType::kWhiteFrequency;
  NoiseIdentificationMethod method = NoiseIdentificationMethod::kNotIdentified;
};

// Riley & Greenhall (2004), their identification algorithm on frequency data: with d = 0 and z the
// averages, r1 = autocorrelation(z) and delta = r1 / (1 + r1); while delta >= 0.25 and d <
// max_differences, z is differenced and d incremented; then p = -2 (delta + d), alpha = p. A
// d-th difference of the averaged frequency is a (d+1)-th difference of the decimated phase, so
// max_differences is 1 for the Allan variances (their dmax = 2) and 2 for the Hadamard variances
// (dmax = 3). Returns the unrounded p, or nothing when the series is too short or constant.
std::optional<double> lag1_alpha(const AveragedFrequencySeries& averages, std::size_t max_differences);

// Howe et al. (2000) Table 3: the expected B1 ratio (N-sample over 2-sample variance, no dead time)
// of N frequency values for the Allan-variance slope mu (sigma^2 ~ tau^mu), mu = -2 .. 2.
double b1_expected(double n, int mu);

// Howe et al. (2000) Table 4: the mu whose expected B1 is nearest to `b1`, the boundaries being the
// geometric means of neighbouring expectations (the arithmetic mean between mu = 2 and 1).
int b1_mu(double b1, double n);

// The noise of one estimator at one averaging factor from the engine's sums (the OADEV sums are
// always there). At least kLag1MinimumAverages averages: lag1_alpha, rounded (max_differences 2
// for HDEV and OHDEV, else 1). Fewer: B1 = the sample variance of the non-overlapping averages
// over their Allan variance (half the mean square of their first differences), compared with
// b1_expected for N = the estimator's number of terms; mu = 1, 0, -1 give alpha = -2, -1, 0
// (mu = 2 is clamped to random walk FM). For the overlapping estimators that N is large, which
// moves the boundaries up: at long taus a random walk FM record then reads as white or flicker FM,
// as in Stable32. B1 cannot tell white from flicker PM (both mu = -2): for MDEV, R(n) = MVAR/AVAR
// picks white PM, flicker PM or, above their boundary with white FM, white FM; the unmodified
// estimators take white FM, as Stable32 reports. These are the choices that reproduce every alpha
// Stable32 published for the three data sets of data/stable32 (with identify_along_taus; the rule
// used before, and how this one was found, are in data/stable32/README.md).
// Fewer than 2 averages or a constant record: white FM, not identified.
NoiseIdentification identify_power_law_noise(Estimator estimator, const AllanSums& sums);

// identify_power_law_noise at every averaging factor of a run (sums in increasing order), except
// that the longest one, when it has fewer than kLag1MinimumAverages averages and a shorter one
// exists, takes the identification of the next shorter one (method kShorterTau), as Stable32 does:
// identified on their own, the longest taus of 5 of the 17 published Stable32 curves in
// data/stable32 disagree with its alpha; carried over, none does. With so few averages (4 to 19
// there) B1 scatters across a boundary; the next shorter tau has twice as many.
std::vector<NoiseIdentification> identify_along_taus(Estimator estimator, std::span<const AllanSums> sums);

}  // namespace inertest

// Power spectral density of a rate record by Welch's method (issue 19), the noise terms read off it
// (IEEE Std 952-1997 Annex C) and its periodic components.
//
// Welch (Welch, "The use of fast Fourier transform for the estimation of power spectra", IEEE Trans.
// Audio Electroacoust. AU-15, 1967): the record is cut into segments of `segment_length` samples
// that overlap by `overlap`; each segment's mean is removed (so that a rate record's bias does not
// leak into the lowest bins), it is multiplied by the window w, transformed (FFTW, r2c) and its
// periodogram |X_k|^2 averaged over the segments (compensated sums). The density is one-sided, in
// (U)^2/Hz for samples in U:
//   S1(f_k) = c_k / (fs sum_n w_n^2) * mean over segments |X_k|^2,  f_k = k fs / L, k = 0..L/2,
// with c_k = 2 except at 0 Hz and (L even) the Nyquist frequency, where c_k = 1 (the normalisation of
// scipy.signal.welch, scaling="density", detrend="constant"). Then sum_k S1(f_k) fs / L equals the
// windowed mean square of the mean-removed segments (Parseval), and a sinusoid of peak amplitude A
// adds A^2 / 2 to the sum over its bins. The amplitude spectral density is sqrt(S1), in (U)/sqrt(Hz).
//
// Windows, periodic (DFT-even) as scipy.signal.get_window makes them (Harris, "On the use of windows
// for harmonic analysis with the discrete Fourier transform", Proc. IEEE 66, 1978): rectangular,
// hann (0.5 - 0.5 cos), hamming (0.54 - 0.46 cos), blackman-harris (4-term, 0.35875 - 0.48829 cos
// + 0.14128 cos 2x - 0.01168 cos 3x). The rectangular window's sidelobes fall as 1/f^2, as fast as a
// rate random walk's spectrum: it overstates steep spectra and suits only flat ones.
//
// Degrees of freedom of each bin (Percival & Walden, "Spectral Analysis for Physical Applications",
// 1993, 6.17, eq. 292b; Welch 1967): nu = 2 K / (1 + 2 sum_{m=1}^{K-1} (1 - m/K) rho(m)^2), K segments,
// rho(m) = sum_n w_n w_{n+mD} / sum_n w_n^2 the window's overlap correlation at a shift of m steps D;
// nu / 2 at 0 Hz and at the Nyquist frequency. A mean over M neighbouring bins has the edf
// nu M^2 / sum_{i,j} |c(i - j)|^2, c(d) = sum_n w_n^2 exp(-2 pi i d n / L) / sum_n w_n^2 the
// correlation of bins d apart (Percival & Walden 6.17; exact for a spectrum flat over the bins, and
// the two corrections taken as separable).
//
// Noise terms. IEEE Std 952-1997 Annex C gives, next to each term's Allan variance (C.1, eqs.
// C.2-C.12, numbered as the simulator cites them, src/sim/noise.cc: Q C.2, N C.3, B C.5, K C.7,
// R C.8), its
// rate PSD S2(f), TWO-sided (eq. C.1: sigma^2 = 4 int_0^inf S2 sin^4(pi f tau) / (pi f tau)^2 df):
// quantization (2 pi f)^2 tau0 Q^2, white rate N^2, bias instability (B^2 / 2 pi) / f, rate random
// walk (K / 2 pi)^2 / f^2, rate ramp R^2 / (2 pi f)^3. The Welch PSD is ONE-sided, S1 = 2 S2:
//   S1(f) = 2 [ (2 pi f)^2 tau0 Q^2 + N^2 + (B^2 / 2 pi) / f + (K / 2 pi)^2 / f^2 + R^2 / (2 pi f)^3 ]
// (quantization Q with tau0 = 1 / fs, valid below 1 / (2 tau0); angle random walk N; bias instability
// B; rate random walk K; rate ramp R). The worked consequence: white rate noise of N reads a flat
// S1 = 2 N^2, so N = sqrt(S1 / 2), and its one-sided ASD is sqrt(2) N, not N. For white samples of
// standard deviation sigma at fs: S1 = 2 sigma^2 / fs and N = sigma / sqrt(fs).
//
// The record holds the mean rate over each sample interval tau0 (the angle increments over tau0, from
// which the Allan variance is computed): what it shows of a term S(f) of the rate is that averaged
// and aliased, sum_m S(|f + m fs|) sinc^2(pi (f + m fs) tau0). At low frequency that is S(f); near the
// Nyquist frequency it is not (a 1/f term reads 12 % lower there), and the fit uses it: white noise
// stays 2 N^2, quantization (white angle noise of Q, differenced) reads 2 Q^2 4 sin^2(pi f tau0) /
// tau0, the (2 pi f)^2 tau0 Q^2 form times sinc^2(pi f tau0).
//
// The fit is a generalised non-negative least squares (Lawson & Hanson, as the Allan fit,
// noise_terms.h) on the PSD averaged in log-spaced bands (kBandsPerDecade per decade; each band's
// design row is the mean of the terms over its bins), whitened by the covariance of the band means,
// Cov(a, b) = (2 / nu) S_a S_b sum_{i in a, j in b} |c(i - j)|^2 / (M_a M_b) (bins of neighbouring
// bands correlate too), with S from the observed band means on the first pass and from the fitted
// model on the following ones (observed weights bias the fit low). Bins at 0 Hz, at the Nyquist
// frequency, within the window's main lobe of 0 Hz (its response to the mean removal) and those of
// periodic components are left out. Q and R (which act only at the ends of the spectrum and trade
// off against N and K) are held at zero while within 2 of their 1-sigma uncertainties of zero. (The
// Allan fit no longer eliminates Q, noise_terms.h; here Q's f^2 rise is seen over the whole upper
// decade, and left free on records without quantisation its bound pulled N low: over 1000 seeds of
// white noise and rate random walk, N's mean z went from -0.27 to -0.59.) Each coefficient's
// 1-sigma uncertainty is from the covariance (J^T V^-1 J)^-1, scaled by the reduced chi-squared
// when that exceeds 1; a coefficient held at zero is "not identified", with the upper bound
// max(0, a) + 2 s of its unconstrained estimate a and uncertainty s. The figures have the names and
// units of NoiseTerms: deg/sqrt(h), deg/h, deg/h/sqrt(h) (and arcsec, deg/h/h) for an angular-rate
// input unit; (U)*sqrt(s), U, (U)/sqrt(s) (and (U)*s, (U)/s) otherwise.
// The rate ramp is deterministic: the form R^2 / (2 pi f)^3 does not describe what a ramp leaves in a
// Welch PSD whose segments have their means removed (and Hann confines most of the remaining trend to
// the bins the fit leaves out). R stays in the model so that a ramp's leakage does not bias K or B,
// but its figure understates a ramp (a simulated 360 deg/h/h on white noise read 146 +- 19): a
// warning says so when it is identified, and compare_noise_terms does not compare it.
//
// Periodic components: a bin k whose S1 exceeds t times the local noise floor. The floor is the
// median of the bins k-m..k+m (m up to kFloorHalfWidth beyond the guard), leaving out the guard
// |d| <= main-lobe half-width + 1 around k, divided by the median/mean ratio of a chi-squared of the
// bin's edf nu. The threshold t is the 1 - p quantile of the F distribution F(nu, nu_f) of a bin over
// an estimated floor (nu_f: the edf of the mean of the floor's bins, divided by pi / 2, the variance
// of a median relative to a mean), with p = 1 - (1 - P_FA)^(1/M) over the M bins searched (Sidak,
// "Rectangular confidence regions for the means of multivariate normal distributions", JASA 62, 1967),
// so that pure noise shows a component with probability at most P_FA over the whole spectrum
// (false_alarm_probability; neighbouring bins being correlated, somewhat less). Bins above the
// threshold closer than a main lobe are one component; it covers the main lobe around its highest
// bin. Its frequency is the centroid of the excess S1 - floor over its bins, its peak amplitude
// A = sqrt(2 sum (S1 - floor) fs / L) in U. The frequency's 1-sigma uncertainty from the variance of
// each bin, (2 (S1 - floor) floor + floor^2) 2 / nu (a sinusoid in Gaussian noise); the amplitude's
// from the variance of the summed excess, whose bins correlate: the noise's (2 / nu) sum_{i,j}
// floor_i floor_j |c(i - j)|^2, the sinusoid-noise cross term's 2 P floor fs sum w^4 / (sum w^2)^2
// (1 + 2 sum_m (1 - m/K) r4(m)) / K for a power P = A^2 / 2 (by Parseval, the cross term summed over
// the bins is (2 / sum w^2) sum_n w_n^2 x_n e_n; r4(m) = sum w_n^2 w_{n+mD}^2 / sum w^4 its
// correlation between segments m steps apart), and the floor's.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "inertest/allan/noise_terms.h"
#include "inertest/core/figure.h"

namespace inertest {

enum class SpectralWindow { kRectangular, kHann, kHamming, kBlackmanHarris };

// "rectangular", "hann", "hamming" or "blackman-harris". Throws Error naming the choices otherwise.
SpectralWindow parse_spectral_window(const std::string& text);
// The name parse_spectral_window reads.
std::string spectral_window_name(SpectralWindow window);

struct WelchOptions {
  double sample_rate_hz = 0.0;
  // Samples per segment; 0: automatic, the largest power of two at most 1/16 of the record (31 to 63
  // segments at an overlap of 0.5), at least 16 (or the record, if shorter) and at most 2^20.
  std::size_t segment_length = 0;
  SpectralWindow window = SpectralWindow::kHann;
  double overlap = 0.5;  // fraction of a segment shared with the next, in [0, 1)
  // Probability that pure noise shows a periodic component anywhere in the spectrum, in (0, 1).
  double false_alarm_probability = 1e-3;

  // Throws Error for a rate that is not positive and finite, an overlap outside [0, 1), a
  // segment_length of 1, or a false-alarm probability outside (0, 1).
  void validate() const;
};

// The noise terms read off the PSD (see above): index p + 2 of the arrays is the term of NoiseTerms'
// A_p (Q, N, B, K, R), and coefficients[p + 2] is the square of its figure in the computed unit
// ((U)^2 s^2, (U)^2 s, (U)^2, (U)^2 / s, (U)^2 / s^2).
struct SpectralNoiseTerms {
  Figure quantization;
  Figure angle_random_walk;
  Figure bias_instability;
  Figure rate_random_walk;
  Figure rate_ramp;
  std::array<double, 5> coefficients{};
  std::array<double, 5> coefficient_uncertainties{};
  std::array<bool, 5> identified{};
  // As NoiseTerms::significant: identified and at least 2 sigma above zero; an identified
  // coefficient that is not keeps its figure and gets the upper bound A_p + 2 sigma too.
  std::array<bool, 5> significant{};
  std::array<std::optional<Figure>, 5> upper_bounds;
  double reduced_chi_squared = 0.0;
  std::size_t degrees_of_freedom = 0;
  std::size_t band_count = 0;  // bands fitted
  double frequency_min_hz = 0.0;  // the lowest and highest bins fitted
  double frequency_max_hz = 0.0;
  std::string verdict;  // "consistent", "inconsistent", "undetermined" (no degree of freedom) or "not fitted"

  // As NoiseTerms: each figure a Figure (with "significant": false and "upper_bound" within 2 sigma
  // of zero), one not identified {"value": null, "unit", "identified": false, "upper_bound"}; and "fit": {"model", "reduced_chi_squared", "degrees_of_freedom",
  // "verdict", "band_count", "frequency_min_hz", "frequency_max_hz"}.
  // Keys named for the sensor the input unit measures (noise_term_names).
  nlohmann::json to_json(const std::string& input_unit) const;
};

struct PeriodicComponent {
  Figure frequency;             // Hz: the centroid of the excess power, 1 sigma
  Figure amplitude;             // peak amplitude of the sinusoid, in the input unit, 1 sigma
  double peak_to_floor_ratio = 0.0;  // highest bin's S1 over its floor
  double frequency_low_hz = 0.0;     // the bins it covers
  double frequency_high_hz = 0.0;
};

struct PowerSpectralDensity {
  std::string unit;  // of the samples, U
  double sample_rate_hz = 0.0;
  std::vector<double> frequency_hz;  // k fs / L, k = 0..L/2
  std::vector<double> density;       // one-sided, (U)^2/Hz
  std::vector<double> edf;           // of each bin
  std::size_t segment_length = 0;
  std::size_t segment_count = 0;
  SpectralWindow window = SpectralWindow::kHann;
  double overlap = 0.0;
  double resolution_hz = 0.0;                  // fs / L, the bin spacing
  double equivalent_noise_bandwidth_hz = 0.0;  // fs sum w^2 / (sum w)^2
  // The bins 1..L/2-1 averaged in log-spaced bands (the JSON carries these, not every bin): the band
  // of bin k is floor(kBandsPerDecade log10 k); empty bands are skipped.
  std::vector<double> band_frequency_hz;  // mean frequency of the band's bins
  std::vector<double> band_density;       // mean S1 of the band's bins
  std::vector<double> band_edf;
  // Periodic components, strongest first; the range searched and the false-alarm probability.
  std::vector<PeriodicComponent> peaks;
  double false_alarm_probability = 0.0;
  double peak_search_min_hz = 0.0;
  double peak_search_max_hz = 0.0;
  SpectralNoiseTerms noise;
  std::vector<std::string> warnings;

  // sqrt(density), (U)/sqrt(Hz).
  std::vector<double> amplitude_spectral_density() const;

  // {"method", "window", "segment_length", "segment_count", "overlap", "detrend": "mean",
  //  "resolution_hz", "equivalent_noise_bandwidth_hz", "edf" (of a bin, 0 Hz and Nyquist excepted),
  //  "bands_per_decade", "band_frequency_hz": [...], "band_edf": [...],
  //  "density": {"unit": "(U)^2/Hz", "values": [band means]},
  //  "amplitude_spectral_density": {"unit": "(U)/sqrt(Hz)", "values": [sqrt of the band means]},
  //  "noise_terms": SpectralNoiseTerms::to_json(),
  //  "peaks": [{"frequency": Figure in Hz, "amplitude": Figure in U, "peak_to_floor_ratio",
  //             "frequency_low_hz", "frequency_high_hz"}],
  //  "peak_search": {"false_alarm_probability", "frequency_min_hz", "frequency_max_hz"},
  //  "warnings": [...]}
  nlohmann::json to_json() const;
};

// The Welch PSD of `samples` (in `unit`), its periodic components and its noise terms (see above).
// Throws Error when a sample is not finite, the options are invalid (WelchOptions::validate), the
// record holds fewer than 16 samples, or the segment is longer than the record.
// Thread-safe: FFTW's planner, which is not, is called under a mutex.
PowerSpectralDensity welch_power_spectral_density(std::span<const double> samples, const std::string& unit,
                                                  const WelchOptions& options);

// One warning per term (Q, N, B, K; not R, see above) that both fits identify and whose figures
// differ by more than kDisagreementSigma combined 1-sigma uncertainties sqrt(s_allan^2 + s_psd^2),
// saying by how many; none otherwise.
std::vector<std::string> compare_noise_terms(const NoiseTerms& allan, const SpectralNoiseTerms& psd);

inline constexpr std::size_t kBandsPerDecade = 20;
inline constexpr std::size_t kFloorHalfWidth = 16;
inline constexpr double kDisagreementSigma = 3.0;

}  // namespace inertest

#include "inertest/allan/power_spectral_density.h"

#include <fftw3.h>

#include <Eigen/Dense>
#include <algorithm>
#include <bit>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>
#include <complex>
#include <fmt/format.h>
#include <limits>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <numbers>

#include "allan/noise_figures.h"
#include "inertest/core/error.h"
#include "inertest/numerics/compensated_sum.h"
#include "numerics/non_negative_least_squares.h"

namespace inertest {
namespace {

using detail::coefficient_covariance;
using detail::figure_of;
using detail::kSignificance;  // Q and R held at zero within it (the header), and significant
using detail::noise_figure_json;
using detail::solve_scaled_non_negative;
using detail::units_for;

constexpr double kPi = std::numbers::pi;
constexpr std::size_t kShortestRecord = 16;
constexpr std::size_t kShortestAutomaticSegment = 16;
constexpr std::size_t kLongestAutomaticSegment = std::size_t{1} << 20;
constexpr int kTerms = 5;  // Q, N, B, K, R: index p + 2 of NoiseTerms' A_p
constexpr int kWeightIterations = 3;
// The largest bin distance at which two bins of a cosine-sum window correlate: the square of a
// 4-term window holds cosines up to 6 x.
constexpr std::size_t kLargestBinCorrelation = 6;

// FFTW's planner is not thread-safe (FFTW manual, 5.4 "Thread safety"); fftw_execute is.
std::mutex& planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

// One r2c transform of `length` points, its buffers and plan (FFTW_ESTIMATE: no timing runs).
class RealTransform {
 public:
  explicit RealTransform(std::size_t length)
      : length_(length),
        input_(static_cast<double*>(fftw_malloc(sizeof(double) * length))),
        output_(static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * (length / 2 + 1)))) {
    if (input_ == nullptr || output_ == nullptr) {
      release();
      throw Error(fmt::format("out of memory for an FFT of {} points", length));
    }
    const std::lock_guard lock(planner_mutex());
    plan_ = fftw_plan_dft_r2c_1d(static_cast<int>(length), input_, output_, FFTW_ESTIMATE);
    if (plan_ == nullptr) {
      release();
      throw Error(fmt::format("FFTW could not plan an FFT of {} points", length));
    }
  }
  RealTransform(const RealTransform&) = delete;
  RealTransform& operator=(const RealTransform&) = delete;
  ~RealTransform() { release(); }

  std::span<double> input() { return {input_, length_}; }
  // |X_k|^2, k = 0..length/2, of the input.
  void power(std::vector<double>& out) {
    fftw_execute(plan_);
    out.resize(length_ / 2 + 1);
    for (std::size_t k = 0; k < out.size(); ++k) out[k] = output_[k][0] * output_[k][0] + output_[k][1] * output_[k][1];
  }

 private:
  void release() {
    if (plan_ != nullptr) {
      const std::lock_guard lock(planner_mutex());
      fftw_destroy_plan(plan_);
      plan_ = nullptr;
    }
    fftw_free(input_);
    fftw_free(output_);
    input_ = nullptr;
    output_ = nullptr;
  }

  std::size_t length_;
  double* input_;
  fftw_complex* output_;
  fftw_plan plan_ = nullptr;
};

// Periodic window of `length` points (see the header).
std::vector<double> window_of(SpectralWindow window, std::size_t length) {
  std::vector<double> coefficients;
  switch (window) {
    case SpectralWindow::kRectangular: coefficients = {1.0}; break;
    case SpectralWindow::kHann: coefficients = {0.5, 0.5}; break;
    case SpectralWindow::kHamming: coefficients = {0.54, 0.46}; break;
    case SpectralWindow::kBlackmanHarris: coefficients = {0.35875, 0.48829, 0.14128, 0.01168}; break;
  }
  std::vector<double> w(length);
  for (std::size_t n = 0; n < length; ++n) {
    const double x = 2.0 * kPi * static_cast<double>(n) / static_cast<double>(length);
    double value = 0.0;
    for (std::size_t j = 0; j < coefficients.size(); ++j) {
      value += (j % 2 == 0 ? 1.0 : -1.0) * coefficients[j] * std::cos(static_cast<double>(j) * x);
    }
    w[n] = value;
  }
  return w;
}

// Half-width of the main lobe in bins (Harris 1978, Table 1): 1, 2, 2, 4.
std::size_t main_lobe_half_width(SpectralWindow window) {
  switch (window) {
    case SpectralWindow::kRectangular: return 1;
    case SpectralWindow::kHann:
    case SpectralWindow::kHamming: return 2;
    case SpectralWindow::kBlackmanHarris: return 4;
  }
  return 1;
}

std::size_t automatic_segment_length(std::size_t samples) {
  const std::size_t length = std::bit_floor(samples / 16);
  if (length < kShortestAutomaticSegment) return std::min(kShortestAutomaticSegment, samples);
  return std::min(length, kLongestAutomaticSegment);
}

// Welch's edf of a bin (the header, Percival & Walden eq. 292b).
double welch_edf(std::span<const double> w, std::size_t step, std::size_t segments) {
  const double energy = [&] {
    CompensatedSum sum;
    for (double v : w) sum.add(v * v);
    return sum.value();
  }();
  const auto k = static_cast<double>(segments);
  double denominator = 1.0;
  for (std::size_t m = 1; m < segments && m * step < w.size(); ++m) {
    CompensatedSum overlap;
    for (std::size_t n = 0; n + m * step < w.size(); ++n) overlap.add(w[n] * w[n + m * step]);
    const double rho = overlap.value() / energy;
    denominator += 2.0 * (1.0 - static_cast<double>(m) / k) * rho * rho;
  }
  return 2.0 * k / denominator;
}

// The variance of the sinusoid-noise cross term of a component's power, in units of 2 S1 P / df
// (S1 the floor, P = A^2 / 2 the component's power, df = fs / L): L sum_n w_n^4 / (sum_n w_n^2)^2
// for one segment, times (1 + 2 sum_{m=1}^{K-1} (1 - m/K) r4(m)) / K over K segments, r4(m) =
// sum_n w_n^2 w_{n+mD}^2 / sum_n w_n^4. By Parseval the cross term summed over the component's
// bins is (2 / sum w^2) sum_n w_n^2 x_n e_n (x the sinusoid, e the noise), whose variance is
// 2 S1 P fs sum w^4 / (sum w^2)^2 for white noise of one-sided level S1 under a sinusoid of power
// P = A^2 / 2; overlapping segments share samples, so their cross terms correlate by r4(m) (as
// their periodograms do by rho(m)^2 in Welch's edf, Percival & Walden eq. 292b). Hann at an
// overlap of 0.5: 35/18 per segment, r4(1) = 3/35.
double cross_term_factor(std::span<const double> w, std::size_t step, std::size_t segments) {
  CompensatedSum energy, fourth;
  for (double v : w) {
    energy.add(v * v);
    fourth.add(v * v * v * v);
  }
  const auto k = static_cast<double>(segments);
  double sum = 1.0;
  for (std::size_t m = 1; m < segments && m * step < w.size(); ++m) {
    CompensatedSum overlap;
    for (std::size_t n = 0; n + m * step < w.size(); ++n) overlap.add(w[n] * w[n] * w[n + m * step] * w[n + m * step]);
    sum += 2.0 * (1.0 - static_cast<double>(m) / k) * overlap.value() / fourth.value();
  }
  return static_cast<double>(w.size()) * fourth.value() / (energy.value() * energy.value()) * sum / k;
}

// |c(d)|^2, d = 0..kLargestBinCorrelation: the squared correlation of bins d apart (the header).
std::array<double, kLargestBinCorrelation + 1> bin_correlations(std::span<const double> w) {
  std::array<double, kLargestBinCorrelation + 1> result{};
  double energy = 0.0;
  for (double v : w) energy += v * v;
  for (std::size_t d = 0; d <= kLargestBinCorrelation; ++d) {
    std::complex<double> sum = 0.0;
    for (std::size_t n = 0; n < w.size(); ++n) {
      sum += w[n] * w[n] * std::polar(1.0, -2.0 * kPi * static_cast<double>(d * n % w.size()) / static_cast<double>(w.size()));
    }
    result[d] = std::norm(sum / energy);
  }
  return result;
}

// The edf of the mean of the bins `bins` (sorted), each of edf nu.
double mean_edf(std::span<const std::size_t> bins, double nu,
                const std::array<double, kLargestBinCorrelation + 1>& correlation) {
  double pairs = 0.0;
  for (std::size_t i = 0; i < bins.size(); ++i) {
    pairs += correlation[0];
    for (std::size_t j = i + 1; j < bins.size() && bins[j] - bins[i] <= kLargestBinCorrelation; ++j) {
      pairs += 2.0 * correlation[bins[j] - bins[i]];
    }
  }
  const auto m = static_cast<double>(bins.size());
  return nu * m * m / pairs;
}

// The bins 1..last grouped by band floor(kBandsPerDecade log10 k), skipping `excluded` bins.
std::vector<std::vector<std::size_t>> bands_of(std::size_t first, std::size_t last, const std::vector<bool>& excluded) {
  std::vector<std::vector<std::size_t>> bands;
  long current = -1;
  for (std::size_t k = first; k <= last; ++k) {
    if (excluded[k]) continue;
    const auto band = static_cast<long>(std::floor(static_cast<double>(kBandsPerDecade) * std::log10(static_cast<double>(k)) + 1e-9));
    if (band != current) {
      bands.emplace_back();
      current = band;
    }
    bands.back().push_back(k);
  }
  return bands;
}

double median_of(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  if (values.size() % 2 == 1) return *middle;
  return 0.5 * (*middle + *std::max_element(values.begin(), middle));
}

// Periodic components (the header); `in_peak` marks the bins they cover.
void find_peaks(PowerSpectralDensity& psd, const std::array<double, kLargestBinCorrelation + 1>& correlation,
                double cross_factor, std::vector<bool>& in_peak) {
  const std::size_t bins = psd.density.size();
  const std::size_t lobe = main_lobe_half_width(psd.window);
  const std::size_t guard = lobe + 1;
  const std::size_t shortest = guard + 4;  // at least 4 floor bins on each side
  const double nu = psd.edf[1];
  in_peak.assign(bins, false);
  if (bins < 2 * shortest + 3) {
    psd.warnings.push_back(fmt::format("periodic components: {} bins are too few to estimate a noise floor", bins));
    return;
  }
  const std::size_t first = shortest + 1;
  const std::size_t last = bins - 2 - shortest;
  psd.peak_search_min_hz = psd.frequency_hz[first];
  psd.peak_search_max_hz = psd.frequency_hz[last];
  const auto searched = static_cast<double>(last - first + 1);
  // Sidak: 1 - (1 - P)^(1/M), by log1p for a small P.
  const double bin_probability = -std::expm1(std::log1p(-psd.false_alarm_probability) / searched);
  const boost::math::chi_squared_distribution<double> chi_squared(nu);
  const double median_to_mean = boost::math::quantile(chi_squared, 0.5) / nu;
  std::map<std::size_t, double> threshold_by_half_width;
  std::vector<double> floor(bins, 0.0);
  std::vector<bool> above(bins, false);
  std::vector<double> floor_edf(bins, 0.0);
  for (std::size_t k = first; k <= last; ++k) {
    const std::size_t m = std::min({guard + kFloorHalfWidth, k - 1, bins - 2 - k});
    std::vector<double> neighbours;
    std::vector<std::size_t> neighbour_bins;
    for (std::size_t j = k - m; j <= k + m; ++j) {
      if (j + guard >= k && j <= k + guard) continue;
      neighbours.push_back(psd.density[j]);
      neighbour_bins.push_back(j);
    }
    floor[k] = median_of(std::move(neighbours)) / median_to_mean;
    floor_edf[k] = mean_edf(neighbour_bins, nu, correlation) / (kPi / 2.0);
    auto threshold = threshold_by_half_width.find(m);
    if (threshold == threshold_by_half_width.end()) {
      const boost::math::fisher_f_distribution<double> ratio(nu, floor_edf[k]);
      threshold = threshold_by_half_width.emplace(m, boost::math::quantile(boost::math::complement(ratio, bin_probability))).first;
    }
    above[k] = floor[k] > 0.0 && psd.density[k] > threshold->second * floor[k];
  }
  // Runs of bins above the threshold, closer than a main lobe, are one component.
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  for (std::size_t k = first; k <= last; ++k) {
    if (!above[k]) continue;
    if (!runs.empty() && k - runs.back().second <= lobe) {
      runs.back().second = k;
    } else {
      runs.emplace_back(k, k);
    }
  }
  const double df = psd.resolution_hz;
  for (const auto& [run_first, run_last] : runs) {
    std::size_t highest = run_first;
    for (std::size_t k = run_first; k <= run_last; ++k) {
      if (psd.density[k] / floor[k] > psd.density[highest] / floor[highest]) highest = k;
    }
    const std::size_t low = std::min(run_first, highest - std::min(highest - 1, lobe));
    const std::size_t high = std::min(std::max(run_last, highest + lobe), bins - 2);
    // The floor of the highest bin, where the bins at the component's edges have none of their own.
    const auto floor_at = [&](std::size_t k) { return floor[k] > 0.0 ? floor[k] : floor[highest]; };
    CompensatedSum excess, moment, floor_sum;
    // The variance of the sum of the excess over the bins (in (S1)^2, times df^2 below): the noise
    // alone, (2 / nu) sum_{i,j} floor_i floor_j |c(i - j)|^2 (bins of one window correlate, as in
    // mean_edf), and the sinusoid-noise cross term, 2 sum_k e_k floor_k times cross_factor
    // (cross_term_factor; a bin's 2 e floor 2 / nu would count it as if the bins and the segments
    // were independent, which understates it by about 35/18 for Hann: measured over 1000 seeds, the
    // amplitude scattered 1.39 times its uncertainty so computed).
    double noise_variance = 0.0;
    double cross_variance = 0.0;
    for (std::size_t k = low; k <= high; ++k) {
      const double fl = floor_at(k);
      const double e = psd.density[k] - fl;
      excess.add(e);
      moment.add(psd.frequency_hz[k] * e);
      floor_sum.add(fl);
      for (std::size_t j = low; j <= high; ++j) {
        const std::size_t d = j > k ? j - k : k - j;
        if (d <= kLargestBinCorrelation) noise_variance += fl * floor_at(j) * correlation[d] * 2.0 / psd.edf[k];
      }
      cross_variance += 2.0 * std::max(0.0, e) * fl * cross_factor;
      in_peak[k] = true;
    }
    const double excess_variance = noise_variance + cross_variance;
    if (!(excess.value() > 0.0)) continue;
    const double centroid = moment.value() / excess.value();
    double centroid_variance = 0.0;
    for (std::size_t k = low; k <= high; ++k) {
      const double fl = floor_at(k);
      const double lever = (psd.frequency_hz[k] - centroid) / excess.value();
      centroid_variance += lever * lever * (2.0 * std::max(0.0, psd.density[k] - fl) * fl + fl * fl) * 2.0 / psd.edf[k];
    }
    const double floor_variance = floor_sum.value() * floor_sum.value() * 2.0 / floor_edf[highest];
    const double power = excess.value() * df;  // A^2 / 2
    const double amplitude = std::sqrt(2.0 * power);
    PeriodicComponent component;
    component.frequency = Figure{centroid, "Hz", std::sqrt(centroid_variance)};
    component.amplitude = Figure{amplitude, psd.unit, std::sqrt(excess_variance + floor_variance) * df / amplitude};
    component.peak_to_floor_ratio = psd.density[highest] / floor[highest];
    component.frequency_low_hz = psd.frequency_hz[low];
    component.frequency_high_hz = psd.frequency_hz[high];
    psd.peaks.push_back(component);
  }
  std::sort(psd.peaks.begin(), psd.peaks.end(),
            [](const PeriodicComponent& a, const PeriodicComponent& b) { return a.amplitude.value > b.amplitude.value; });
}

// The terms of the model per unit coefficient, as the record sees them (the header): S1(f) =
// sum_j c_j g_j(f), each continuous term averaged over the sample interval and aliased. Q's is the
// discrete form, N's exactly 2 (sum_m sinc^2(pi (x + m)) = 1); B's, K's and R's alias sums are cut
// at |m| = kAliases, which leaves out less than 1e-3 of B's at the Nyquist frequency.
constexpr int kAliases = 16;

std::array<double, kTerms> model_terms(double f, double tau0) {
  const double s = std::sin(kPi * f * tau0);
  std::array<double, kTerms> g = {8.0 * s * s / tau0, 2.0, 0.0, 0.0, 0.0};
  for (int m = -kAliases; m <= kAliases; ++m) {
    const double alias = std::abs(f + m / tau0);
    const double w = 2.0 * kPi * alias;
    const double x = kPi * alias * tau0;
    const double sinc_squared = std::pow(std::sin(x) / x, 2);
    g[2] += sinc_squared * 2.0 / w;
    g[3] += sinc_squared * 2.0 / (w * w);
    g[4] += sinc_squared * 2.0 / (w * w * w);
  }
  return g;
}

std::vector<Eigen::Index> free_columns(const std::vector<bool>& free) {
  std::vector<Eigen::Index> columns;
  for (std::size_t j = 0; j < free.size(); ++j) {
    if (free[j]) columns.push_back(static_cast<Eigen::Index>(j));
  }
  return columns;
}

struct TermSpec {
  Figure SpectralNoiseTerms::*figure;
  detail::FigureUnits units;
};

// The figures in the units of NoiseTerms (noise_terms.h).
std::array<TermSpec, kTerms> term_specs(const std::string& unit) {
  return {TermSpec{&SpectralNoiseTerms::quantization, units_for(unit, -2)},
          TermSpec{&SpectralNoiseTerms::angle_random_walk, units_for(unit, -1)},
          TermSpec{&SpectralNoiseTerms::bias_instability, units_for(unit, 0)},
          TermSpec{&SpectralNoiseTerms::rate_random_walk, units_for(unit, 1)},
          TermSpec{&SpectralNoiseTerms::rate_ramp, units_for(unit, 2)}};
}

constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();

void fit_noise(PowerSpectralDensity& psd, const std::array<double, kLargestBinCorrelation + 1>& correlation,
               const std::vector<bool>& in_peak) {
  SpectralNoiseTerms& terms = psd.noise;
  const std::array<TermSpec, kTerms> specs = term_specs(psd.unit);
  const std::size_t bins = psd.density.size();
  const std::size_t first = main_lobe_half_width(psd.window) + 1;
  std::vector<std::vector<std::size_t>> bands;
  if (bins >= first + 2) bands = bands_of(first, bins - 2, in_peak);
  const auto rows = static_cast<Eigen::Index>(bands.size());
  terms.band_count = bands.size();
  const auto not_fitted = [&](const std::string& reason) {
    terms.verdict = "not fitted";
    psd.warnings.push_back("noise terms from the PSD: " + reason + ": not fitted");
    for (const TermSpec& spec : specs) terms.*spec.figure = figure_of(0.0, kUnknown, 1.0, spec.units);
  };
  if (rows < kTerms + 1) {
    not_fitted(fmt::format("{} bands, fewer than the {} the fit needs", rows, kTerms + 1));
    return;
  }
  const double tau0 = 1.0 / psd.sample_rate_hz;
  Eigen::MatrixXd design(rows, kTerms);
  Eigen::VectorXd observed(rows);
  for (Eigen::Index b = 0; b < rows; ++b) {
    const std::vector<std::size_t>& band = bands[static_cast<std::size_t>(b)];
    CompensatedSum mean;
    std::array<double, kTerms> row{};
    for (std::size_t k : band) {
      mean.add(psd.density[k]);
      const auto g = model_terms(psd.frequency_hz[k], tau0);
      for (int j = 0; j < kTerms; ++j) row[static_cast<std::size_t>(j)] += g[static_cast<std::size_t>(j)];
    }
    const auto m = static_cast<double>(band.size());
    observed(b) = mean.value() / m;
    for (int j = 0; j < kTerms; ++j) design(b, j) = row[static_cast<std::size_t>(j)] / m;
  }
  if (!(observed.minCoeff() > 0.0)) {
    not_fitted("a band of zero power (a constant record?)");
    return;
  }
  // Fitted on the band means divided by the largest, as the Allan fit is (noise_terms.cc): the
  // model is linear in its coefficients, and the covariance of the bands (of the order of S^2)
  // stays within the range of a double for records of any magnitude.
  const double scale = observed.maxCoeff();
  if (!std::isfinite(scale)) {
    not_fitted("a band of infinite power (samples too large)");
    return;
  }
  observed /= scale;
  // The correlation of the band means: Cov(a, b) = (2 / nu) S_a S_b sum_{i in a, j in b} |c(i - j)|^2
  // / (M_a M_b) (the header; its diagonal is 2 S_a^2 / edf_a). Bins of neighbouring bands correlate
  // too: at low frequency, where each band is a bin, Hann's neighbours by |c(1)|^2 = 4/9.
  // Summed over the pairs of bins at most kLargestBinCorrelation apart, found through each bin's band.
  constexpr auto kNoBand = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> band_of(bins, kNoBand);
  for (std::size_t b = 0; b < bands.size(); ++b) {
    for (std::size_t k : bands[b]) band_of[k] = b;
  }
  Eigen::MatrixXd overlap = Eigen::MatrixXd::Zero(rows, rows);
  for (std::size_t i = 0; i < bins; ++i) {
    if (band_of[i] == kNoBand) continue;
    for (std::size_t j = i >= kLargestBinCorrelation ? i - kLargestBinCorrelation : 0;
         j < bins && j <= i + kLargestBinCorrelation; ++j) {
      if (band_of[j] != kNoBand) {
        overlap(static_cast<Eigen::Index>(band_of[i]), static_cast<Eigen::Index>(band_of[j])) +=
            correlation[i > j ? i - j : j - i];
      }
    }
  }
  for (Eigen::Index a = 0; a < rows; ++a) {
    for (Eigen::Index b = 0; b < rows; ++b) {
      overlap(a, b) *= 2.0 / psd.edf[1] /
                       (static_cast<double>(bands[static_cast<std::size_t>(a)].size()) *
                        static_cast<double>(bands[static_cast<std::size_t>(b)].size()));
    }
  }
  terms.frequency_min_hz = psd.frequency_hz[bands.front().front()];
  terms.frequency_max_hz = psd.frequency_hz[bands.back().back()];
  // Whitened by the Cholesky factor of that covariance, with S the observed band mean on the first
  // pass and the model's afterwards.
  Eigen::VectorXd level = observed;
  Eigen::MatrixXd whitened_design;
  Eigen::VectorXd whitened_observed;
  Eigen::VectorXd a = Eigen::VectorXd::Zero(kTerms);
  std::vector<bool> allowed(kTerms, true);
  std::vector<bool> free;
  const auto solve = [&] {
    const Eigen::LLT<Eigen::MatrixXd> factor(level.asDiagonal() * overlap * level.asDiagonal());
    whitened_design = factor.matrixL().solve(design);
    whitened_observed = factor.matrixL().solve(observed);
    a = solve_scaled_non_negative(whitened_design, whitened_observed, allowed, free);
  };
  const auto reweight = [&] {
    for (int pass = 0; pass < kWeightIterations; ++pass) {
      const Eigen::VectorXd model = design * a;
      for (Eigen::Index b = 0; b < rows; ++b) level(b) = model(b) > 0.0 ? model(b) : observed(b);
      solve();
    }
  };
  const auto reduced_chi_squared = [&] {
    const auto free_count = static_cast<std::size_t>(std::count(free.begin(), free.end(), true));
    terms.degrees_of_freedom = bands.size() > free_count ? bands.size() - free_count : 0;
    const double chi_squared = (whitened_design * a - whitened_observed).squaredNorm();
    return terms.degrees_of_freedom > 0 ? chi_squared / static_cast<double>(terms.degrees_of_freedom) : 0.0;
  };
  solve();
  reweight();
  // Backward elimination of Q (0) and R (4) (the header: the Allan fit eliminates R only).
  for (;;) {
    const std::vector<Eigen::Index> columns = free_columns(free);
    if (columns.size() <= 1) break;
    const Eigen::MatrixXd covariance = coefficient_covariance(whitened_design, columns);
    const double inflation = std::max(1.0, reduced_chi_squared());
    std::optional<std::size_t> weakest;
    double weakest_z = kSignificance;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (columns[c] != 0 && columns[c] != kTerms - 1) continue;
      const auto e = static_cast<Eigen::Index>(c);
      const double z = a(columns[c]) / std::sqrt(inflation * covariance(e, e));
      if (z < weakest_z) {
        weakest_z = z;
        weakest = static_cast<std::size_t>(columns[c]);
      }
    }
    if (!weakest) break;
    allowed[*weakest] = false;
    solve();
  }
  reweight();
  terms.reduced_chi_squared = reduced_chi_squared();
  const bool consistent = terms.degrees_of_freedom > 0 &&
                          terms.reduced_chi_squared <= 1.0 + 3.0 * std::sqrt(2.0 / static_cast<double>(terms.degrees_of_freedom));
  terms.verdict = terms.degrees_of_freedom == 0 ? "undetermined" : consistent ? "consistent" : "inconsistent";
  if (terms.verdict == "inconsistent") {
    psd.warnings.push_back(fmt::format(
        "noise terms from the PSD: the model of IEEE 952 Annex C does not fit the bands from {:.4g} to {:.4g} Hz "
        "(reduced chi-squared {:.3g} over {} degrees of freedom): its figures are doubtful",
        terms.frequency_min_hz, terms.frequency_max_hz, terms.reduced_chi_squared, terms.degrees_of_freedom));
  }
  const double inflation = std::max(1.0, terms.reduced_chi_squared);
  const std::vector<Eigen::Index> columns = free_columns(free);
  const Eigen::MatrixXd covariance = coefficient_covariance(whitened_design, columns);
  for (Eigen::Index j = 0; j < kTerms; ++j) {
    const auto k = static_cast<std::size_t>(j);
    const TermSpec& spec = specs[k];
    terms.coefficients[k] = scale * a(j);
    const auto place = std::find(columns.begin(), columns.end(), j);
    if (place != columns.end()) {
      const auto c = place - columns.begin();
      terms.coefficient_uncertainties[k] = scale * std::sqrt(inflation * covariance(c, c));
      terms.identified[k] = true;
      terms.*spec.figure = figure_of(terms.coefficients[k], terms.coefficient_uncertainties[k], 1.0, spec.units);
      terms.significant[k] = terms.coefficients[k] >= kSignificance * terms.coefficient_uncertainties[k];
      if (!terms.significant[k]) {
        terms.upper_bounds[k] =
            figure_of(terms.coefficients[k] + kSignificance * terms.coefficient_uncertainties[k], kUnknown, 1.0, spec.units);
      }
      continue;
    }
    // Held at zero: freed along with the free ones, its unconstrained estimate and uncertainty give
    // the bound.
    std::vector<Eigen::Index> with_it = columns;
    with_it.push_back(j);
    Eigen::MatrixXd sub(rows, static_cast<Eigen::Index>(with_it.size()));
    for (std::size_t c = 0; c < with_it.size(); ++c) sub.col(static_cast<Eigen::Index>(c)) = whitened_design.col(with_it[c]);
    const Eigen::MatrixXd joint = coefficient_covariance(whitened_design, with_it);
    const Eigen::VectorXd unconstrained = joint * (sub.transpose() * whitened_observed);
    const Eigen::Index last = joint.rows() - 1;
    const double sigma = std::sqrt(inflation * joint(last, last));
    terms.identified[k] = false;
    terms.coefficient_uncertainties[k] = scale * sigma;
    terms.*spec.figure = figure_of(0.0, kUnknown, 1.0, spec.units);
    terms.upper_bounds[k] = figure_of(scale * (std::max(0.0, unconstrained(last)) + kSignificance * sigma),
                                      kUnknown, 1.0, spec.units);
  }
  if (terms.identified[kTerms - 1]) {
    psd.warnings.push_back(
        "noise terms from the PSD: the rate ramp R read off the PSD understates a deterministic ramp (each segment's "
        "mean removal takes most of it out); the Allan fit's R is the one to use");
  }
}

}  // namespace

SpectralWindow parse_spectral_window(const std::string& text) {
  for (SpectralWindow window : {SpectralWindow::kRectangular, SpectralWindow::kHann, SpectralWindow::kHamming,
                                SpectralWindow::kBlackmanHarris}) {
    if (text == spectral_window_name(window)) return window;
  }
  throw Error(fmt::format("unknown spectral window '{}': use rectangular, hann, hamming or blackman-harris", text));
}

std::string spectral_window_name(SpectralWindow window) {
  switch (window) {
    case SpectralWindow::kRectangular: return "rectangular";
    case SpectralWindow::kHann: return "hann";
    case SpectralWindow::kHamming: return "hamming";
    case SpectralWindow::kBlackmanHarris: return "blackman-harris";
  }
  return "hann";
}

void WelchOptions::validate() const {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw Error(fmt::format("the sample rate must be positive and finite (got {} Hz)", sample_rate_hz));
  }
  if (!(overlap >= 0.0 && overlap < 1.0)) {
    throw Error(fmt::format("the segment overlap must lie in [0, 1) (got {})", overlap));
  }
  if (segment_length == 1) throw Error("the segment length must be at least 2 samples (got 1)");
  if (!(false_alarm_probability > 0.0 && false_alarm_probability < 1.0)) {
    throw Error(fmt::format("the false-alarm probability must lie in (0, 1) (got {})", false_alarm_probability));
  }
}

std::vector<double> PowerSpectralDensity::amplitude_spectral_density() const {
  std::vector<double> asd(density.size());
  std::transform(density.begin(), density.end(), asd.begin(), [](double s) { return std::sqrt(s); });
  return asd;
}

PowerSpectralDensity welch_power_spectral_density(std::span<const double> samples, const std::string& unit,
                                                  const WelchOptions& options) {
  options.validate();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!std::isfinite(samples[i])) throw Error(fmt::format("sample {} is not finite ({})", i + 1, samples[i]));
  }
  if (samples.size() < kShortestRecord) {
    throw Error(fmt::format("a PSD needs at least {} samples (got {})", kShortestRecord, samples.size()));
  }
  const std::size_t length = options.segment_length > 0 ? options.segment_length : automatic_segment_length(samples.size());
  if (length > samples.size()) {
    throw Error(fmt::format("the segment length {} is longer than the record ({} samples)", length, samples.size()));
  }
  const std::size_t step = std::max<std::size_t>(
      1, length - static_cast<std::size_t>(std::floor(options.overlap * static_cast<double>(length))));
  const std::size_t segments = (samples.size() - length) / step + 1;
  const std::vector<double> w = window_of(options.window, length);
  CompensatedSum window_sum, window_energy;
  for (double v : w) {
    window_sum.add(v);
    window_energy.add(v * v);
  }

  PowerSpectralDensity psd;
  psd.unit = unit;
  psd.sample_rate_hz = options.sample_rate_hz;
  psd.segment_length = length;
  psd.segment_count = segments;
  psd.window = options.window;
  psd.overlap = options.overlap;
  psd.false_alarm_probability = options.false_alarm_probability;
  psd.resolution_hz = options.sample_rate_hz / static_cast<double>(length);
  psd.equivalent_noise_bandwidth_hz =
      options.sample_rate_hz * window_energy.value() / (window_sum.value() * window_sum.value());

  const std::size_t bins = length / 2 + 1;
  std::vector<CompensatedSum> sums(bins);
  {
    RealTransform transform(length);
    std::vector<double> power;
    // Each segment's mean is taken about the record's first sample: a mean stored near an offset of
    // 1e8 is rounded to 1.5e-8, and that DC left in, windowed, leaked into the lowest bins (8e-5 of
    // the first band for noise of 1e-3); the differences from a sample near them are exact.
    const double reference = samples.front();
    for (std::size_t s = 0; s < segments; ++s) {
      const std::span<const double> segment = samples.subspan(s * step, length);
      CompensatedSum sum;
      for (const double v : segment) sum.add(v - reference);
      const double mean = sum.value() / static_cast<double>(length);
      std::span<double> input = transform.input();
      for (std::size_t n = 0; n < length; ++n) input[n] = ((segment[n] - reference) - mean) * w[n];
      transform.power(power);
      for (std::size_t k = 0; k < bins; ++k) sums[k].add(power[k]);
    }
  }
  const double scale = 1.0 / (options.sample_rate_hz * window_energy.value() * static_cast<double>(segments));
  const double nu = welch_edf(w, step, segments);
  for (std::size_t k = 0; k < bins; ++k) {
    const bool unpaired = k == 0 || (length % 2 == 0 && k == bins - 1);  // 0 Hz and Nyquist
    psd.frequency_hz.push_back(static_cast<double>(k) * psd.resolution_hz);
    psd.density.push_back((unpaired ? 1.0 : 2.0) * scale * sums[k].value());
    psd.edf.push_back(unpaired ? nu / 2.0 : nu);
  }
  const auto correlation = bin_correlations(w);
  if (bins >= 3) {
    const auto bands = bands_of(1, bins - 2, std::vector<bool>(bins, false));
    for (const std::vector<std::size_t>& band : bands) {
      CompensatedSum frequency, density;
      for (std::size_t k : band) {
        frequency.add(psd.frequency_hz[k]);
        density.add(psd.density[k]);
      }
      const auto m = static_cast<double>(band.size());
      psd.band_frequency_hz.push_back(frequency.value() / m);
      psd.band_density.push_back(density.value() / m);
      psd.band_edf.push_back(mean_edf(band, nu, correlation));
    }
  }
  if (options.window == SpectralWindow::kRectangular) {
    psd.warnings.push_back(
        "rectangular window: its leakage falls as 1/f^2, as fast as a rate random walk; steep spectra are overstated");
  }
  std::vector<bool> in_peak;
  find_peaks(psd, correlation, cross_term_factor(w, step, segments), in_peak);
  fit_noise(psd, correlation, in_peak);
  return psd;
}

std::vector<std::string> compare_noise_terms(const NoiseTerms& allan, const SpectralNoiseTerms& psd) {
  struct Term {
    const Figure& allan;
    const Figure& psd;
  };
  // Index p + 2 of A_p; the rate ramp is not compared (see the header).
  const std::array<Term, 4> terms = {Term{allan.quantization, psd.quantization},
                                     Term{allan.angle_random_walk, psd.angle_random_walk},
                                     Term{allan.bias_instability, psd.bias_instability},
                                     Term{allan.rate_random_walk, psd.rate_random_walk}};
  // B is in the input's own dimension (deg/h, ug, ...): it tells the sensor, and so the names.
  SensorKind kind = SensorKind::kGyro;
  if (!allan.bias_instability.unit.empty()) kind = sensor_kind_of(allan.bias_instability.unit);
  const auto& names = noise_term_names(kind);
  std::vector<std::string> warnings;
  for (std::size_t k = 0; k < terms.size(); ++k) {
    if (!allan.identified[k] || !psd.identified[k]) continue;
    const Figure& a = terms[k].allan;
    const Figure b = terms[k].psd.in(a.unit);
    const double sigma = std::hypot(a.uncertainty.value_or(0.0), b.uncertainty.value_or(0.0));
    const double difference = std::abs(a.value - b.value);
    if (!(sigma > 0.0) || difference <= kDisagreementSigma * sigma) continue;
    warnings.push_back(fmt::format(
        "{}: the Allan fit gives {:.4g} +- {:.2g} {}, the PSD {:.4g} +- {:.2g} {}: they differ by {:.1f} combined sigma",
        names[k].label, a.value, a.uncertainty.value_or(0.0), a.unit, b.value, b.uncertainty.value_or(0.0), a.unit,
        difference / sigma));
  }
  return warnings;
}

nlohmann::json SpectralNoiseTerms::to_json(const std::string& input_unit) const {
  const auto& names = noise_term_names(sensor_kind_of(input_unit));
  return {{names[0].key, noise_figure_json(quantization, identified[0], significant[0], upper_bounds[0])},
          {names[1].key, noise_figure_json(angle_random_walk, identified[1], significant[1], upper_bounds[1])},
          {names[2].key, noise_figure_json(bias_instability, identified[2], significant[2], upper_bounds[2])},
          {names[3].key, noise_figure_json(rate_random_walk, identified[3], significant[3], upper_bounds[3])},
          {names[4].key, noise_figure_json(rate_ramp, identified[4], significant[4], upper_bounds[4])},
          {"fit",
           {{"model",
             "S1(f) = 2 [(2 pi f)^2 tau0 Q^2 + N^2 + B^2 / (2 pi f) + K^2 / (2 pi f)^2 + R^2 / (2 pi f)^3] "
             "(IEEE 952 Annex C, one-sided), non-negative weighted least squares on log-spaced band means"},
            {"reduced_chi_squared", reduced_chi_squared},
            {"degrees_of_freedom", degrees_of_freedom},
            {"verdict", verdict},
            {"band_count", band_count},
            {"frequency_min_hz", frequency_min_hz},
            {"frequency_max_hz", frequency_max_hz}}}};
}

nlohmann::json PowerSpectralDensity::to_json() const {
  nlohmann::json peaks_json = nlohmann::json::array();
  for (const PeriodicComponent& peak : peaks) {
    peaks_json.push_back({{"frequency", peak.frequency},
                          {"amplitude", peak.amplitude},
                          {"peak_to_floor_ratio", peak.peak_to_floor_ratio},
                          {"frequency_low_hz", peak.frequency_low_hz},
                          {"frequency_high_hz", peak.frequency_high_hz}});
  }
  std::vector<double> band_asd(band_density.size());
  std::transform(band_density.begin(), band_density.end(), band_asd.begin(), [](double s) { return std::sqrt(s); });
  return {{"method", "Welch, one-sided, mean removed per segment"},
          {"window", spectral_window_name(window)},
          {"segment_length", segment_length},
          {"segment_count", segment_count},
          {"overlap", overlap},
          {"detrend", "mean"},
          {"resolution_hz", resolution_hz},
          {"equivalent_noise_bandwidth_hz", equivalent_noise_bandwidth_hz},
          {"edf", edf.size() > 1 ? edf[1] : 0.0},
          {"bands_per_decade", kBandsPerDecade},
          {"band_frequency_hz", band_frequency_hz},
          {"band_edf", band_edf},
          {"density", {{"unit", "(" + unit + ")^2/Hz"}, {"values", band_density}}},
          {"amplitude_spectral_density", {{"unit", "(" + unit + ")/sqrt(Hz)"}, {"values", band_asd}}},
          {"noise_terms", noise.to_json(unit)},
          {"peaks", peaks_json},
          {"peak_search",
           {{"false_alarm_probability", false_alarm_probability},
            {"frequency_min_hz", peak_search_min_hz},
            {"frequency_max_hz", peak_search_max_hz}}},
          {"warnings", warnings}};
}

}  // namespace inertest

#include "inertest/allan/allan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <type_traits>

#include "inertest/allan/tau_grid.h"
#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/numerics/compensated_sum.h"

namespace inertest {
namespace {

std::vector<std::size_t> averaging_factors_for(std::size_t sample_count, const AllanOptions& options) {
  const TauGrid grid = TauGrid::parse(options.taus);
  const std::size_t largest = largest_averaging_factor(sample_count, options.estimators);
  if (largest == 0) {
    throw Error("too few samples: " + std::to_string(sample_count) + " sample(s) support no averaging time (" +
                (options.estimators.needs_third_differences() ? "MDEV, HDEV and OHDEV need at least 3"
                                                              : "ADEV, OADEV and TOTDEV need at least 2") +
                ")");
  }
  std::vector<std::size_t> factors = grid.averaging_factors(options.sample_rate_hz, largest);
  if (factors.empty()) {
    throw Error(fmt::format("no tau of the grid '{}' fits the record: {} samples at {} Hz support tau up to {} s",
                            options.taus, sample_count, options.sample_rate_hz,
                            static_cast<double>(largest) / options.sample_rate_hz));
  }
  return factors;
}

void compute_bounds(AllanResult& result) {
  for (auto& [estimator, curve] : result.curves) {
    curve.edf.resize(curve.values.size());
    curve.lower.resize(curve.values.size());
    curve.upper.resize(curve.values.size());
    for (std::size_t i = 0; i < curve.values.size(); ++i) {
      curve.edf[i] = equivalent_degrees_of_freedom(estimator, result.sample_count, result.averaging_factors[i],
                                                   curve.noise_types[i]);
      const DeviationInterval interval = chi_squared_interval(curve.values[i], curve.edf[i], result.confidence);
      curve.lower[i] = interval.lower;
      curve.upper[i] = interval.upper;
    }
  }
}

// The power-law noise whose term A_p tau^p of the fitted model (GJB 2426A eq. 30) is the largest at
// tau: p = -2 quantisation (white PM), -1 angle random walk (white FM), 0 bias instability
// (flicker FM), 1 and 2 rate random walk and rate ramp (random walk FM, the reddest type the edf
// formulae know).
NoiseType dominant_noise(const NoiseTerms& fit, double tau) {
  int dominant = -2;
  double largest = -1.0;
  for (int p = -2; p <= 2; ++p) {
    const double term = fit.coefficients[static_cast<std::size_t>(p + 2)] * std::pow(tau, p);
    if (term > largest) {
      largest = term;
      dominant = p;
    }
  }
  switch (dominant) {
    case -2: return NoiseType::kWhitePhase;
    case -1: return NoiseType::kWhiteFrequency;
    case 0: return NoiseType::kFlickerFrequency;
    default: return NoiseType::kRandomWalkFrequency;
  }
}

// The points the noise terms are fitted on: every tau of an octave or decade grid, but of a denser
// one (--taus all) only those an octave or more apart, the octave grid's own points where it holds
// them. The fit's covariance has a row and a column per point and its decomposition grows as the cube
// of their count: 25 000 samples at every tau (8333 points) took 390 s and 1.4 GB. And the fit is
// validated on octave grids: on eight points an octave the angle random walk of 6000 white-noise
// samples came out 3.3 % off the truth with a 0.6 % uncertainty (fit_noise_terms warns of such
// grids). The curves and their bounds keep every tau.
std::vector<std::size_t> noise_fit_points(const std::vector<double>& tau_s) {
  std::vector<std::size_t> points;
  double next = 0.0;
  for (std::size_t i = 0; i < tau_s.size(); ++i) {
    const double octave = std::log2(tau_s[i]);
    if (points.empty() || octave >= next) {
      points.push_back(i);
      next = octave + (1.0 - 1e-9);  // the next tau of an octave grid is kept whatever its rounding
    }
  }
  return points;
}

void identify_noise(AllanResult& result, const std::optional<FitRange>& fit_range) {
  const DeviationCurve* basis = nullptr;
  Estimator basis_estimator = Estimator::kOadev;
  for (Estimator e : {Estimator::kOadev, Estimator::kAdev, Estimator::kTotdev}) {
    if (result.curves.contains(e)) {
      basis = &result.curves.at(e);
      basis_estimator = e;
      break;
    }
  }
  if (basis == nullptr) {
    result.warnings.push_back("noise terms need OADEV, ADEV or TOTDEV: not identified");
    return;
  }
  if (result.tau_s.size() < 2) {
    result.warnings.push_back("noise terms need at least 2 averaging times: not identified");
    return;
  }
  for (double value : basis->values) {
    if (!(value > 0.0)) {
      result.warnings.push_back("a deviation is zero (constant record?): noise terms not identified");
      return;
    }
  }
  const std::vector<std::size_t> points = noise_fit_points(result.tau_s);
  std::vector<double> tau_s;
  std::vector<double> variances;
  for (std::size_t i : points) {
    tau_s.push_back(result.tau_s[i]);
    variances.push_back(basis->values[i] * basis->values[i]);
  }
  NoiseFitOptions fit_options;
  fit_options.fit_range = fit_range;
  fit_options.sample_count = result.sample_count;
  fit_options.sample_interval_s = 1.0 / result.sample_rate_hz;
  // The fit weighs each point by its covariance under the model (noise_terms.h), so the edf of a
  // point is that of the noise the model says dominates there: a first fit on the edf of the noise
  // identified from the data (lag-1 autocorrelation, SP 1065 section 5.6, which also sets the
  // reported bounds) finds the model, the second fit uses the model's edf. Identification from the
  // data scatters where few terms remain (B1, R(n)) and would weigh those points by the scatter.
  // In the model of GJB eq. (30) the dominant noise only reddens as tau grows (quantisation, white,
  // flicker, random walk FM, IEEE 952 C.1: alpha 2, 0, -1, -2), so for the first fit a type bluer
  // than the one at the shorter tau is taken as a misidentification and replaced by it: a white-FM
  // record whose B1 ratio read "flicker PM" at two long taus (edf 15x too large) otherwise makes the
  // whole curve look inconsistent, and the automatic range then drops every short tau (measured: N
  // 26 sigma off the truth on 2e6 samples of white noise).
  std::vector<double> first_edf;
  NoiseType reddest = basis->noise_types.empty() ? NoiseType::kWhitePhase : basis->noise_types.front();
  for (std::size_t i : points) {
    reddest = static_cast<NoiseType>(std::min(static_cast<int>(reddest), static_cast<int>(basis->noise_types[i])));
    first_edf.push_back(equivalent_degrees_of_freedom(basis_estimator, result.sample_count,
                                                      result.averaging_factors[i], reddest));
  }
  const NoiseTerms first = fit_noise_terms(tau_s, variances, first_edf, result.input_unit, fit_options);
  std::vector<double> model_edf;
  for (std::size_t i : points) {
    model_edf.push_back(equivalent_degrees_of_freedom(basis_estimator, result.sample_count, result.averaging_factors[i],
                                                      dominant_noise(first, result.tau_s[i])));
  }
  result.noise = fit_noise_terms(tau_s, variances, model_edf, result.input_unit, fit_options);
  result.warnings.insert(result.warnings.end(), result.noise->warnings.begin(), result.noise->warnings.end());
  result.slopes = read_noise_slopes(result.tau_s, basis->values, basis->edf, result.input_unit);
  result.warnings.insert(result.warnings.end(), result.slopes->warnings.begin(), result.slopes->warnings.end());
}

AllanResult assemble(std::size_t sample_count, double mean, const std::vector<AllanSums>& sums,
                     const AllanOptions& options) {
  AllanResult result;
  result.sample_count = sample_count;
  result.sample_rate_hz = options.sample_rate_hz;
  result.input_unit = options.input_unit;
  result.tau_grid = options.taus;
  result.confidence = options.confidence;
  result.mean = Figure{mean * options.scale, options.input_unit, std::nullopt};
  for (const AllanSums& s : sums) {
    result.averaging_factors.push_back(s.averaging_factor);
    result.tau_s.push_back(static_cast<double>(s.averaging_factor) / options.sample_rate_hz);
  }
  for (const NoiseIdentification& noise : identify_along_taus(Estimator::kAdev, sums)) {
    result.noise_types.push_back(noise.type);
  }
  for (Estimator e : options.estimators.members()) {
    DeviationCurve& curve = result.curves[e];
    curve.unit = options.input_unit;
    for (const AllanSums& s : sums) {
      // The sums of squared differences are of the samples' magnitude squared times m^2 N: beyond
      // about 1e150 they overflow (inf, or NaN from inf - inf), which max(0, NaN) would read as 0.
      if (!std::isfinite(s.variance(e))) {
        throw Error(fmt::format("the {} at tau = {:g} s overflows a double: the samples are too large (give them "
                                "in a larger unit)",
                                estimator_name(e), static_cast<double>(s.averaging_factor) / options.sample_rate_hz));
      }
      curve.values.push_back(std::abs(options.scale) * std::sqrt(std::max(0.0, s.variance(e))));
      curve.terms.push_back(s.terms(e));
    }
    for (const NoiseIdentification& noise : identify_along_taus(e, sums)) {
      curve.noise_types.push_back(noise.type);
      curve.noise_methods.push_back(noise.method);
    }
  }
  compute_bounds(result);
  // Taus asked for by value that the record cannot support are left out, and said: the curve had
  // them missing without a word. (Those that name one factor twice are one tau.)
  const TauGrid grid = TauGrid::parse(options.taus);
  if (grid.kind == TauGrid::Kind::kExplicit) {
    std::vector<std::string> beyond;
    for (double tau : grid.taus_s) {
      const auto m = static_cast<std::size_t>(std::llround(tau * options.sample_rate_hz));
      if (!std::binary_search(result.averaging_factors.begin(), result.averaging_factors.end(), m)) {
        beyond.push_back(fmt::format("{:g} s", tau));
      }
    }
    if (!beyond.empty()) {
      result.warnings.push_back(fmt::format(
          "tau {} left out: {} samples support tau up to {:g} s with these estimators", fmt::join(beyond, ", "),
          result.sample_count, static_cast<double>(largest_averaging_factor(result.sample_count, options.estimators)) /
                                   options.sample_rate_hz));
    }
  }
  identify_noise(result, options.fit_range);
  return result;
}

AllanEngineOptions engine_options(std::vector<std::size_t> factors, const AllanOptions& options) {
  AllanEngineOptions engine;
  engine.averaging_factors = std::move(factors);
  engine.estimators = options.estimators;
  engine.worker_count = options.worker_count;
  engine.ring_capacity_limit = options.ring_capacity_limit;
  return engine;
}

// Bytes of the process besides the ring: the read buffers (4 MB of bytes, up to 8 MB of samples),
// the engine's scratch, the code and libraries.
constexpr std::size_t kMemoryReserveBytes = 32u << 20;
// Below this the ring is never limited (the fixed costs of the process dominate anyway).
constexpr std::size_t kSmallestRingLimitBytes = 64u << 20;

// The ring limit that keeps the peak resident memory within 1.5 times the raw binary size of the
// record (issue bound): 8 bytes per sample for text, the file size for raw binary and records of named
// channels (.mat, HDF5, TDMS). Text records
// cannot be read at random, and their 8 (N+1)-byte ring is within the bound anyway: no limit.
std::size_t automatic_ring_limit(const RateRecordSource& source) {
  if (source.format == RateRecordFormat::kCsv) return 0;
  const auto raw = static_cast<std::size_t>(std::filesystem::file_size(source.path));
  const std::size_t budget = raw + raw / 2 > kMemoryReserveBytes ? raw + raw / 2 - kMemoryReserveBytes : 0;
  return std::max(budget, kSmallestRingLimitBytes) / sizeof(double);
}

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

// Random access to a raw binary record, for the engine's second pass.
SampleReader binary_sample_reader(const RateRecordSource& source) {
  const std::size_t size = source.binary.sample_size();
  std::shared_ptr<std::FILE> file(std::fopen(source.path.c_str(), "rb"), FileCloser{});
  if (!file) throw Error(SourceLocation{source.path, 0, 0}, std::string("cannot open: ") + std::strerror(errno));
  auto bytes = std::make_shared<std::vector<char>>();
  return [file, bytes, size, format = source.binary, path = source.path](std::size_t first, std::span<double> out) {
    bytes->resize(out.size() * size);
    if (fseeko(file.get(), static_cast<off_t>(first * size), SEEK_SET) != 0 ||
        std::fread(bytes->data(), 1, bytes->size(), file.get()) != bytes->size()) {
      throw Error(SourceLocation{path, 0, 0}, "read error in the second pass (did the file change?)");
    }
    decode_binary_frames(std::string_view(bytes->data(), bytes->size()), format, out);
  };
}

// A provisional offset for the engine: the mean of the first samples of the record (up to 2^20,
// the first chunk a reader hands over; the exact mean comes from the phase total). The phase then
// drifts by k (mean - offset), which the differences cancel; the closer the offset, the smaller the
// phase values and their rounding.
double provisional_offset(std::span<const double> first) {
  first = first.first(std::min<std::size_t>(first.size(), std::size_t{1} << 20));
  return compensated_sum(first) / static_cast<double>(first.size());
}

nlohmann::json noise_type_names(const std::vector<NoiseType>& types) {
  nlohmann::json names = nlohmann::json::array();
  for (NoiseType type : types) names.push_back(noise_type_name(type));
  return names;
}

// alpha, the exponent of S_y(f) ~ f^alpha: 2 white PM .. -2 random walk FM.
nlohmann::json noise_alphas(const std::vector<NoiseType>& types) {
  nlohmann::json alphas = nlohmann::json::array();
  for (NoiseType type : types) alphas.push_back(static_cast<int>(type));
  return alphas;
}

// The PSD of the scaled record (when the options ask for it).
std::optional<PowerSpectralDensity> power_spectral_density_of(std::span<const double> rate, const AllanOptions& options) {
  if (!options.psd) return std::nullopt;
  WelchOptions welch = *options.psd;
  welch.sample_rate_hz = options.sample_rate_hz;
  std::vector<double> scaled;
  if (options.scale != 1.0) {
    scaled.reserve(rate.size());
    for (double y : rate) scaled.push_back(y * options.scale);
    rate = scaled;
  }
  return welch_power_spectral_density(rate, options.input_unit, welch);
}

// The PSD, its warnings, and those of its comparison with the Allan fit.
void add_power_spectral_density(AllanResult& result, std::optional<PowerSpectralDensity> psd) {
  if (!psd) return;
  result.psd = std::move(psd);
  for (const std::string& warning : result.psd->warnings) result.warnings.push_back("psd: " + warning);
  if (result.noise) {
    for (const std::string& warning : compare_noise_terms(*result.noise, result.psd->noise)) {
      result.warnings.push_back(warning);
    }
  }
}

}  // namespace

void AllanOptions::validate() const {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw Error(fmt::format("the sample rate must be positive and finite (got {} Hz)", sample_rate_hz));
  }
  Unit::parse(input_unit);
  TauGrid::parse(taus);
  if (estimators.empty()) throw Error("no estimator selected");
  if (!(scale != 0.0) || !std::isfinite(scale)) throw Error("the scale must be finite and nonzero");
  if (!(confidence > 0.0 && confidence < 1.0)) throw Error("the confidence level must lie between 0 and 1");
  if (worker_count == 0) throw Error("at least one worker thread is needed");
  NoiseFitOptions fit_options;
  fit_options.fit_range = fit_range;
  fit_options.validate();
  if (psd) {
    WelchOptions welch = *psd;
    welch.sample_rate_hz = sample_rate_hz;
    welch.validate();
  }
}

// allan_variance, with the record pushed into the engine's ring (a span of const samples) or with
// the engine in place on the samples (a span of samples it may overwrite).
template <typename Sample>
AllanResult analyse_samples(std::span<Sample> rate, const AllanOptions& options) {
  options.validate();
  for (std::size_t i = 0; i < rate.size(); ++i) {
    if (!std::isfinite(rate[i])) throw Error("sample " + std::to_string(i + 1) + " is not a finite number");
  }
  auto factors = averaging_factors_for(rate.size(), options);
  std::optional<PowerSpectralDensity> psd = power_spectral_density_of(rate, options);  // before the samples go
  // One pass: the phase is integrated about a provisional offset, and the mean is offset + X_N / N.
  const double offset = provisional_offset(rate);
  std::vector<AllanSums> sums;
  double phase_total = 0.0;
  if constexpr (std::is_const_v<Sample>) {
    AllanEngine engine(rate.size(), offset, engine_options(std::move(factors), options));
    engine.push(rate);
    sums = engine.finish([rate](std::size_t first, std::span<double> out) {
      std::copy_n(rate.begin() + static_cast<std::ptrdiff_t>(first), out.size(), out.begin());
    });
    phase_total = engine.phase_total();
  } else {
    AllanEngine engine(rate, offset, engine_options(std::move(factors), options));
    sums = engine.finish();
    phase_total = engine.phase_total();
  }
  AllanResult result = assemble(rate.size(), offset + phase_total / static_cast<double>(rate.size()), sums, options);
  add_power_spectral_density(result, std::move(psd));
  return result;
}

AllanResult allan_variance(std::span<const double> rate, const AllanOptions& options) {
  return analyse_samples(rate, options);
}

AllanResult allan_variance_in_place(std::span<double> rate, const AllanOptions& options) {
  return analyse_samples(rate, options);
}

namespace {

// A streamed record into the engine's ring: the binary reader writes its samples there
// (SampleDestination), a record of named channels pushes its chunks. The engine is made at the
// first chunk, read into a buffer of its own: the phase is integrated about that chunk's mean.
class EngineFeed final : public SampleDestination {
 public:
  EngineFeed(std::string path, std::size_t count, AllanEngineOptions setup, const ProgressCallback& progress)
      : path_(std::move(path)), count_(count), setup_(std::move(setup)), progress_(progress) {}

  std::span<double> room() override {
    if (!engine_) {
      first_.resize(kFirstChunk);  // the binary reader's chunk of 256 KiB, of 2-byte samples at the most
      return first_;
    }
    if (pushed_ == count_) throw Error(SourceLocation{path_, 0, 0}, "the file changed while it was read");
    return engine_->room();
  }
  void filled(std::size_t count) override {
    if (!engine_) {
      push(std::span<const double>(first_.data(), count));
      return;
    }
    engine_->commit(count);
    advance(count);
  }
  void push(std::span<const double> samples) {
    if (samples.empty()) return;
    if (!engine_) {
      offset_ = provisional_offset(samples);
      engine_ = std::make_unique<AllanEngine>(count_, offset_, std::move(setup_));
    }
    if (pushed_ + samples.size() > count_) throw Error(SourceLocation{path_, 0, 0}, "the file changed while it was read");
    engine_->push(samples);
    advance(samples.size());
  }
  AllanEngine* engine() const { return engine_.get(); }
  double offset() const { return offset_; }

 private:
  static constexpr std::size_t kFirstChunk = std::size_t{128} << 10;
  void advance(std::size_t count) {
    pushed_ += count;
    if (progress_ && pushed_ - reported_ >= count_ / 100 + 1) {
      reported_ = pushed_;
      progress_("Allan variance", static_cast<double>(pushed_) / static_cast<double>(count_));
    }
  }

  std::string path_;
  std::size_t count_;
  AllanEngineOptions setup_;
  const ProgressCallback& progress_;
  std::vector<double> first_;
  std::unique_ptr<AllanEngine> engine_;
  double offset_ = 0.0;
  std::size_t pushed_ = 0;
  std::size_t reported_ = 0;
};

}  // namespace

AllanResult allan_variance_of_file(const RateRecordSource& given_source, const AllanOptions& options,
                                   const ProgressCallback& progress) {
  options.validate();
  RateRecordSource source = given_source;
  source.format = resolve_rate_record_format(given_source);
  if (source.format == RateRecordFormat::kCsv) {
    // Text is parsed once, in parallel, into memory and analysed there: a second parse would cost
    // more than the 8 bytes a sample. Binary records stream once (below).
    if (progress) progress("reading " + source.path, 0.0);
    std::vector<double> samples = read_text_rate_record(source);
    return allan_variance_in_place(samples, options);
  }
  if (options.psd) {
    // Welch's segments need the samples at hand: the record is read into memory, 8 bytes a sample.
    std::vector<double> samples;
    read_rate_record(source, [&samples](std::span<const double> chunk) {
      samples.insert(samples.end(), chunk.begin(), chunk.end());
    });
    if (const std::optional<ChannelRecordFormat> channel_format = channel_record_format_of(source.format)) {
      const std::unique_ptr<ChannelRecord> record = open_channel_record(source.path, *channel_format);
      resolve_sample_rate(*record, record->find(source.column), options.sample_rate_hz);
    }
    if (samples.empty()) throw Error(SourceLocation{source.path, 0, 0}, "no data: the record is empty");
    return allan_variance_in_place(samples, options);
  }
  // A record of named channels is opened once for both passes and the random reads of the second.
  std::unique_ptr<ChannelRecord> record;
  std::size_t channel = 0;
  if (const std::optional<ChannelRecordFormat> channel_format = channel_record_format_of(source.format)) {
    record = open_channel_record(source.path, *channel_format);
    channel = record->find(source.column);
    resolve_sample_rate(*record, channel, options.sample_rate_hz);
  }
  const auto stream = [&](const SampleSink& sink) {
    return record ? stream_channel(*record, channel, sink) : read_rate_record(source, sink);
  };
  // The record is read once: its length comes from the file (raw) or the channel's header, the
  // engine integrates the phase about the mean of the first chunk, and the mean is offset + X_N / N.
  std::size_t count = 0;
  if (record) {
    count = static_cast<std::size_t>(record->channels()[channel].length);
  } else {
    const std::size_t sample_size = source.binary.sample_size();
    const auto bytes = static_cast<std::size_t>(std::filesystem::file_size(source.path));
    count = bytes % sample_size == 0 ? bytes / sample_size : 0;
  }
  if (count == 0) {
    // Empty or truncated: the reader says which, with the file's name.
    stream([](std::span<const double>) {});
    throw Error(SourceLocation{source.path, 0, 0}, "no data: the record is empty");
  }
  std::vector<std::size_t> factors;
  try {
    factors = averaging_factors_for(count, options);
  } catch (const Error&) {
    // A record the reader rejects (a NaN, a truncated sample) says so first, as when it was read
    // before the taus were chosen.
    stream([](std::span<const double>) {});
    throw;
  }
  AllanEngineOptions engine_setup = engine_options(std::move(factors), options);
  if (engine_setup.ring_capacity_limit == 0) engine_setup.ring_capacity_limit = automatic_ring_limit(source);
  EngineFeed feed(source.path, count, std::move(engine_setup), progress);
  const std::size_t again = record ? stream_channel(*record, channel, [&feed](std::span<const double> samples) { feed.push(samples); })
                                   : read_binary_rate_record(source, feed);
  if (again != count) throw Error(SourceLocation{source.path, 0, 0}, "the file changed while it was read");
  AllanEngine* const engine = feed.engine();
  SampleReader reader;
  if (engine->deferred_factor_count() > 0) {
    if (progress) progress("Allan variance (largest taus, second pass)", 1.0);
    if (record) {
      reader = [&record, channel](std::size_t first, std::span<double> out) { record->read(channel, first, out); };
    } else {
      reader = binary_sample_reader(source);
    }
  }
  const auto sums = engine->finish(reader);
  if (progress) progress("Allan variance", 1.0);
  const double mean = feed.offset() + engine->phase_total() / static_cast<double>(count);
  return assemble(count, mean, sums, options);
}

nlohmann::json AllanResult::to_json() const {
  nlohmann::json json = {{"procedure", "allan_variance"},
                         {"clause", kAllanClause},
                         {"standard", "GJB 2426A-2004 5.12.5.4.2; IEEE Std 952-1997 Annex C; NIST SP 1065"},
                         {"sample_count", sample_count},
                         {"sample_rate_hz", sample_rate_hz},
                         {"record_length", Figure{static_cast<double>(sample_count) / sample_rate_hz, "s", std::nullopt}},
                         {"input_unit", input_unit},
                         {"mean", mean},
                         {"tau_grid", tau_grid},
                         {"confidence_level", confidence},
                         {"tau", tau_s},
                         {"averaging_factor", averaging_factors}};
  json["noise_type"] = noise_type_names(noise_types);
  json["alpha"] = noise_alphas(noise_types);
  for (const auto& [estimator, curve] : curves) {
    nlohmann::json methods = nlohmann::json::array();
    for (NoiseIdentificationMethod method : curve.noise_methods) {
      methods.push_back(noise_identification_method_name(method));
    }
    json[std::string(estimator_name(estimator))] = {{"unit", curve.unit},
                                                    {"values", curve.values},
                                                    {"lower", curve.lower},
                                                    {"upper", curve.upper},
                                                    {"edf", curve.edf},
                                                    {"terms", curve.terms},
                                                    {"edf_method", std::string(edf_method(estimator))},
                                                    {"noise_type", noise_type_names(curve.noise_types)},
                                                    {"alpha", noise_alphas(curve.noise_types)},
                                                    {"noise_identification", methods}};
  }
  if (noise) {
    json["noise"] = noise->to_json(input_unit);
    if (slopes) json["noise"]["slope_method"] = slopes->to_json(input_unit);
  } else {
    json["noise"] = nullptr;
  }
  if (psd) json["psd"] = psd->to_json();
  json["warnings"] = warnings;
  return json;
}

std::string AllanResult::report() const {
  std::string text = fmt::format("Allan variance (GJB 2426A-2004 5.12.5.4.2, IEEE Std 952-1997 Annex C)\n"
                                 "  {} samples at {} Hz, mean {:.6g} {}, deviations in {}\n",
                                 sample_count, sample_rate_hz, mean.value, input_unit, input_unit);
  text += fmt::format("  {:>12} {:>5}", "tau (s)", "alpha");
  for (const auto& [estimator, curve] : curves) text += fmt::format(" {:>12}", estimator_name(estimator));
  text += "\n";
  for (std::size_t i = 0; i < tau_s.size(); ++i) {
    text += fmt::format("  {:>12.6g} {:>5}", tau_s[i], static_cast<int>(noise_types[i]));
    for (const auto& [estimator, curve] : curves) text += fmt::format(" {:>12.5g}", curve.values[i]);
    text += "\n";
  }
  text += "  alpha: dominant noise S_y ~ f^alpha (2 white PM, 1 flicker PM, 0 white FM, -1 flicker FM, -2 random walk FM)\n";
  const auto& names = noise_term_names(sensor_kind_of(input_unit));
  const auto line = [](const std::string& name, const Figure& f) {
    return fmt::format("  {:<28} {:.5g} ± {:.2g} {}\n", name, f.value, f.uncertainty.value_or(0.0), f.unit);
  };
  // A fitted noise term (Allan or PSD): its figure; within 2 sigma of zero, the figure "not
  // significant" with its coefficient's z and bound; held at zero, "not identified" with the bound.
  const auto term_line = [&line](const std::string& name, const Figure& f, bool identified, bool significant, double z,
                                 const std::optional<Figure>& bound) {
    if (significant) return line(name, f);
    if (identified) {
      return fmt::format("  {:<28} {:.5g} ± {:.2g} {}, not significant (its coefficient {:.1f} sigma from 0; < {:.2g} {})\n",
                         name, f.value, f.uncertainty.value_or(0.0), f.unit, z, bound->value, bound->unit);
    }
    return fmt::format("  {:<28} not identified (< {:.2g} {})\n", name, bound->value, bound->unit);
  };
  if (noise) {
    text += fmt::format("Noise terms (fit of GJB 2426A eq. 30, tau {:g} to {:g} s, {}: {}):\n",
                        noise->fit_range.tau_min_s, noise->fit_range.tau_max_s, noise->fit_range_chosen_by,
                        noise->fit_range_reason);
    const Figure* figures[] = {&noise->quantization, &noise->angle_random_walk, &noise->bias_instability,
                               &noise->rate_random_walk, &noise->rate_ramp};
    for (std::size_t k = 0; k < 5; ++k) {
      text += term_line(std::string(names[k].label), *figures[k], noise->identified[k], noise->significant[k],
                        noise->coefficients[k] / noise->coefficient_uncertainties[k], noise->upper_bounds[k]);
    }
    text += fmt::format("  fit: {} (reduced chi-squared {:.3g}, {} degrees of freedom)\n", noise->verdict,
                        noise->reduced_chi_squared, noise->degrees_of_freedom);
  }
  if (slopes) {
    text += "Slope read-off:\n";
    const auto reading = [&](const std::string& name, const SlopeReading& r) {
      return r.figure ? line(name, *r.figure) : fmt::format("  {:<28} not identified (see the warnings)\n", name);
    };
    text += reading(std::string(names[1].label), slopes->angle_random_walk);
    text += reading(std::string(names[2].label), slopes->bias_instability);
    text += reading(std::string(names[3].label), slopes->rate_random_walk);
  }
  if (psd) {
    text += fmt::format("Power spectral density (Welch, {} window, {} segments of {} samples, {:g} Hz resolution):\n",
                        spectral_window_name(psd->window), psd->segment_count, psd->segment_length, psd->resolution_hz);
    const SpectralNoiseTerms& terms = psd->noise;
    const Figure* figures[] = {&terms.quantization, &terms.angle_random_walk, &terms.bias_instability,
                               &terms.rate_random_walk, &terms.rate_ramp};
    for (std::size_t k = 0; k < 5; ++k) {
      if (!terms.significant[k] && !terms.upper_bounds[k]) continue;  // not fitted
      text += term_line(std::string(names[k].label), *figures[k], terms.identified[k], terms.significant[k],
                        terms.coefficients[k] / terms.coefficient_uncertainties[k], terms.upper_bounds[k]);
    }
    for (const PeriodicComponent& peak : psd->peaks) {
      text += fmt::format("  periodic component at {:.6g} Hz: amplitude {:.4g} ± {:.2g} {} ({:.3g} times the floor)\n",
                          peak.frequency.value, peak.amplitude.value, peak.amplitude.uncertainty.value_or(0.0),
                          peak.amplitude.unit, peak.peak_to_floor_ratio);
    }
  }
  for (const std::string& warning : warnings) text += "warning: " + warning + "\n";
  return text;
}

}  // namespace inertest

#include "inertest/allan/allan.h"

#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

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

NoiseType noise_type_of_power(int power) {
  switch (power) {
    case -2: return NoiseType::kWhitePhase;
    case -1: return NoiseType::kWhiteFrequency;
    case 0: return NoiseType::kFlickerFrequency;
    default: return NoiseType::kRandomWalkFrequency;
  }
}

void compute_bounds(AllanResult& result) {
  for (auto& [estimator, curve] : result.curves) {
    curve.edf.resize(curve.values.size());
    curve.lower.resize(curve.values.size());
    curve.upper.resize(curve.values.size());
    for (std::size_t i = 0; i < curve.values.size(); ++i) {
      curve.edf[i] = equivalent_degrees_of_freedom(estimator, result.sample_count, result.averaging_factors[i],
                                                   curve.terms[i], result.noise_types[i]);
      const DeviationInterval interval = chi_squared_interval(curve.values[i], curve.edf[i], result.confidence);
      curve.lower[i] = interval.lower;
      curve.upper[i] = interval.upper;
    }
  }
}

void identify_noise(AllanResult& result) {
  const DeviationCurve* basis = nullptr;
  for (Estimator e : {Estimator::kOadev, Estimator::kAdev, Estimator::kTotdev}) {
    if (result.curves.contains(e)) {
      basis = &result.curves.at(e);
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
  const auto variances = [&] {
    std::vector<double> v;
    for (double d : basis->values) v.push_back(d * d);
    return v;
  };
  NoiseTerms first = fit_noise_terms(result.tau_s, variances(), basis->edf, result.input_unit);
  for (std::size_t i = 0; i < result.tau_s.size(); ++i) result.noise_types[i] = noise_type_of_power(first.dominant_power[i]);
  compute_bounds(result);
  result.noise = fit_noise_terms(result.tau_s, variances(), basis->edf, result.input_unit);
  result.slopes = read_noise_slopes(result.tau_s, basis->values, basis->edf, result.input_unit);
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
  result.noise_types.assign(sums.size(), NoiseType::kWhiteFrequency);
  for (Estimator e : options.estimators.members()) {
    DeviationCurve& curve = result.curves[e];
    curve.unit = options.input_unit;
    for (const AllanSums& s : sums) {
      curve.values.push_back(std::abs(options.scale) * std::sqrt(std::max(0.0, s.variance(e))));
      curve.terms.push_back(s.terms(e));
    }
  }
  compute_bounds(result);
  identify_noise(result);
  return result;
}

AllanEngineOptions engine_options(std::vector<std::size_t> factors, const AllanOptions& options) {
  AllanEngineOptions engine;
  engine.averaging_factors = std::move(factors);
  engine.estimators = options.estimators;
  engine.worker_count = options.worker_count;
  return engine;
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
}

AllanResult allan_variance(std::span<const double> rate, const AllanOptions& options) {
  options.validate();
  for (std::size_t i = 0; i < rate.size(); ++i) {
    if (!std::isfinite(rate[i])) throw Error("sample " + std::to_string(i + 1) + " is not a finite number");
  }
  auto factors = averaging_factors_for(rate.size(), options);
  const double mean = compensated_sum(rate) / static_cast<double>(rate.size());
  AllanEngine engine(rate.size(), mean, engine_options(std::move(factors), options));
  engine.push(rate);
  return assemble(rate.size(), mean, engine.finish(), options);
}

AllanResult allan_variance_of_file(const RateRecordSource& source, const AllanOptions& options,
                                   const ProgressCallback& progress) {
  options.validate();
  CompensatedSum sum;
  const std::size_t count = read_rate_record(source, [&](std::span<const double> samples) {
    for (double v : samples) sum.add(v);
  });
  const double mean = sum.value() / static_cast<double>(count);
  auto factors = averaging_factors_for(count, options);
  AllanEngine engine(count, mean, engine_options(std::move(factors), options));
  std::size_t pushed = 0;
  std::size_t reported = 0;
  const std::size_t again = read_rate_record(source, [&](std::span<const double> samples) {
    engine.push(samples);
    pushed += samples.size();
    if (progress && pushed - reported >= count / 100 + 1) {
      reported = pushed;
      progress("Allan variance", static_cast<double>(pushed) / static_cast<double>(count));
    }
  });
  if (again != count) throw Error(SourceLocation{source.path, 0, 0}, "the file changed while it was read");
  const auto sums = engine.finish();
  if (progress) progress("Allan variance", 1.0);
  return assemble(count, mean, sums, options);
}

nlohmann::json AllanResult::to_json() const {
  nlohmann::json json = {{"procedure", "allan_variance"},
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
  nlohmann::json types = nlohmann::json::array();
  for (NoiseType type : noise_types) types.push_back(noise_type_name(type));
  json["noise_type"] = types;
  for (const auto& [estimator, curve] : curves) {
    json[std::string(estimator_name(estimator))] = {{"unit", curve.unit},     {"values", curve.values},
                                                    {"lower", curve.lower},   {"upper", curve.upper},
                                                    {"edf", curve.edf},       {"terms", curve.terms}};
  }
  if (noise) {
    json["noise"] = noise->to_json(input_unit);
    if (slopes) json["noise"]["slope_method"] = slopes->to_json();
  } else {
    json["noise"] = nullptr;
  }
  json["warnings"] = warnings;
  return json;
}

std::string AllanResult::report() const {
  std::string text = fmt::format("Allan variance (GJB 2426A-2004 5.12.5.4.2, IEEE Std 952-1997 Annex C)\n"
                                 "  {} samples at {} Hz, mean {:.6g} {}, deviations in {}\n",
                                 sample_count, sample_rate_hz, mean.value, input_unit, input_unit);
  text += fmt::format("  {:>12}", "tau (s)");
  for (const auto& [estimator, curve] : curves) text += fmt::format(" {:>12}", estimator_name(estimator));
  text += "\n";
  for (std::size_t i = 0; i < tau_s.size(); ++i) {
    text += fmt::format("  {:>12.6g}", tau_s[i]);
    for (const auto& [estimator, curve] : curves) text += fmt::format(" {:>12.5g}", curve.values[i]);
    text += "\n";
  }
  const auto line = [](const std::string& name, const Figure& f) {
    return fmt::format("  {:<24} {:.5g} ± {:.2g} {}\n", name, f.value, f.uncertainty.value_or(0.0), f.unit);
  };
  if (noise) {
    text += "Noise terms (fit of GJB 2426A eq. 30):\n";
    text += line("quantization Q", noise->quantization);
    text += line("angle random walk N", noise->angle_random_walk);
    text += line("bias instability B", noise->bias_instability);
    text += line("rate random walk K", noise->rate_random_walk);
    text += line("rate ramp R", noise->rate_ramp);
  }
  if (slopes) {
    text += "Slope read-off:\n";
    text += line("angle random walk N", slopes->angle_random_walk);
    text += line("bias instability B", slopes->bias_instability);
    text += line("rate random walk K", slopes->rate_random_walk);
  }
  for (const std::string& warning : warnings) text += "warning: " + warning + "\n";
  return text;
}

}  // namespace inertest

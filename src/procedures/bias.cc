#include "inertest/procedures/bias.h"

#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/io/output_record.h"
#include "inertest/numerics/statistics.h"
#include "inertest/procedures/bias_stability.h"

namespace inertest {
namespace {

constexpr double kSecondsPerHour = 3600.0;

double to_deg_h(double rad_s) { return rad_s / constants::kDegree * kSecondsPerHour; }

}  // namespace

void BiasOptions::validate() const {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw Error(fmt::format("bias: the sample rate must be positive, got {} Hz", sample_rate_hz));
  }
  validate_conversion();
  if (smoothing_s.empty()) throw Error("bias: no smoothing time given for the bias stability");
  for (double s : smoothing_s) {
    if (!(s > 0.0) || !std::isfinite(s)) throw Error(fmt::format("bias: a smoothing time must be positive, got {} s", s));
  }
}

void BiasOptions::validate_conversion() const {
  if (!input_in_deg_h && (scale_factor == 0.0 || !std::isfinite(scale_factor))) {
    throw Error(fmt::format("bias: the scale factor K must be a nonzero number (output units per deg/s), got {}",
                            scale_factor));
  }
  if (remove_earth_rate) remove_earth_rate->validate();
}

void check_bias_conversion(const ProcedureCall& call, const BiasOptions& options, const std::string& procedure) {
  if (options.input_in_deg_h && call.parameters.contains("scale_factor")) {
    throw ParameterError("scale_factor", procedure + ": the scale factor K and records in deg/h (--input-deg-h; input = "
                                                     "\"deg/h\") exclude each other: records in deg/h are not divided by K");
  }
  if (options.input_in_deg_h && call.pulse_counts) {
    throw ParameterError("output_unit", procedure + ": records in deg/h (--input-deg-h; input = \"deg/h\") are no pulse "
                                                    "counts: leave the output unit out");
  }
  if (!options.input_in_deg_h && !call.parameters.contains("scale_factor")) {
    throw Error(procedure + ": missing the scale factor K (--scale-factor; in a plan scale_factor or [instrument] "
                            "nominal_scale_factor), or records in deg/h (--input-deg-h; input = \"deg/h\")");
  }
  options.validate_conversion();
}

std::vector<double> read_bias_record(const ProcedureCall& call, const std::string& file, const BiasOptions& options) {
  if (!options.input_in_deg_h) {
    require_raw_output(call, file, options.output_unit,
                       "leave K out and give input = \"deg/h\" (--input-deg-h): a stored rate is converted");
    return call.read_record(file);
  }
  // Records of rates: a unit the record stores (HDF5, TDMS) converts its samples to deg/h; another
  // stored unit (V) contradicts deg/h, an Error naming both, and so does one inertest does not know
  // (taken as deg/h, a misspelt deg/s made the bias 3600 times too small).
  std::optional<std::string> stored = call.record_unit(file, std::nullopt);
  if (!stored || Unit::parse(*stored).dimension() != Unit::parse("deg/h").dimension()) {
    stored = call.record_unit(file, "deg/h");
  }
  std::vector<double> samples = call.read_record(file);
  if (const double factor = convert(1.0, *stored, "deg/h"); factor != 1.0) {
    for (double& sample : samples) sample *= factor;
  }
  return samples;
}

double BiasOptions::deg_h_per_output() const { return input_in_deg_h ? 1.0 : kSecondsPerHour / scale_factor; }

namespace {

// Samples beyond about 1e150 (1e308 for a mean) overflow the sums of squares (or of values): an
// error, not a null figure.
[[noreturn]] void throw_overflow(const char* what) {
  throw Error(fmt::format("bias: the {} overflows a double: the samples are too large (give them in a larger unit)",
                          what));
}

}  // namespace

double bias_deg_h(std::span<const double> output, const BiasOptions& options) {
  options.validate_conversion();
  if (output.empty()) throw Error("bias: the record is empty");
  double value = mean(output) * options.deg_h_per_output();  // eq. (19): F̄/K, deg/s -> deg/h
  if (!std::isfinite(value)) throw_overflow("mean");
  if (options.remove_earth_rate) value -= to_deg_h(earth_rate_on_axis(*options.remove_earth_rate));
  return value;
}

BiasResult bias(std::span<const double> output, const BiasOptions& options) {
  options.validate();
  if (output.size() < 2) {
    throw Error(fmt::format("bias: the record holds {} sample(s); at least 2 are needed", output.size()));
  }
  const double scale = options.deg_h_per_output();
  // A standard deviation scales by |1/K|: the sign of K only flips the sign of the bias.
  const double magnitude = std::abs(scale);
  BiasResult result;
  result.samples = output.size();
  result.duration = {static_cast<double>(output.size()) / options.sample_rate_hz, "s", std::nullopt};
  result.bias = {bias_deg_h(output, options), "deg/h", std::nullopt};
  if (options.remove_earth_rate) {
    result.earth_rate_removed = Figure{to_deg_h(earth_rate_on_axis(*options.remove_earth_rate)), "deg/h", std::nullopt};
  }
  // A constant record (a stuck channel) has no spread to measure: its stability and random walk are
  // left out, not 0 (a dead gyro passed every limit on them).
  const std::string constant =
      is_constant(output) ? fmt::format("the record is constant: all {} samples equal {:.10g}{} (a stuck channel?)",
                                        output.size(), output.front(),
                                        unit_suffix(options.input_in_deg_h ? "deg/h" : options.output_unit))
                          : "";
  if (!constant.empty()) result.warnings.push_back(constant + ": no bias stability or random walk is measured");
  // Every figure the record supports; a smoothing time it does not (longer than half the record, not
  // a whole number of samples) and a random walk coefficient it cannot give (a record under 2 s,
  // samples more than 1 s apart) are warnings, not an end to the bias.
  for (std::size_t place = 0; place < options.smoothing_s.size(); ++place) {
    const double s = options.smoothing_s[place];
    StabilityAtSmoothing stability;
    try {
      stability = output_stability(output, options.sample_rate_hz, s);  // eq. (20)
    } catch (const Error& e) {
      result.warnings.push_back(e.message() + " (left out)");
      result.smoothing_left_out.push_back({place, s, e.message()});
      continue;
    }
    if (!constant.empty()) {
      result.smoothing_left_out.push_back({place, s, constant});
      continue;
    }
    if (!std::isfinite(stability.stability * magnitude)) throw_overflow("bias stability");
    std::vector<double> smoothed;
    smoothed.reserve(stability.means.size());
    const double earth = result.earth_rate_removed ? result.earth_rate_removed->value : 0.0;
    for (double mean_output : stability.means) smoothed.push_back(mean_output * scale - earth);
    result.bias_stability.push_back(
        {s, stability.windows, Figure{stability.stability * magnitude, "deg/h", std::nullopt}, std::move(smoothed)});
  }
  if (options.random_walk && constant.empty()) {
    result.normalised_stability_curve = normalised_stability_curve(output, options.sample_rate_hz);
    for (auto& point : result.normalised_stability_curve) point.stability *= magnitude;
    try {
      const double ner = noise_equivalent_rate(output, options.sample_rate_hz) * magnitude;  // deg/h
      result.noise_equivalent_rate = Figure{ner, "deg/h", std::nullopt};
      // Eq. (24) with τ = 1 s: NER·√τ in deg/h·√s, converted to deg/√h.
      const double tau_s = 1.0;
      result.random_walk_coefficient =
          Figure{convert(ner * std::sqrt(tau_s), "deg/h*sqrt(s)", "deg/sqrt(h)"), "deg/sqrt(h)", std::nullopt};
    } catch (const Error& e) {
      result.warnings.push_back(e.message() + " (noise equivalent rate and random walk coefficient left out)");
    }
  }
  return result;
}

}  // namespace inertest

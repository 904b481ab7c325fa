#include "inertest/sim/accelerometer_model.h"

#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/units.h"

namespace inertest::sim {

void AccelerometerParameters::validate() const {
  if (!(sample_rate_hz > 0.0)) throw Error(fmt::format("accelerometer: sample_rate_hz must be positive (got {})", sample_rate_hz));
  if (scale_factor == 0.0 || !std::isfinite(scale_factor)) throw Error("accelerometer: scale_factor must be nonzero");
  if (!(noise_ug_rt_hz >= 0.0)) throw Error("accelerometer: noise_ug_rt_hz must not be negative");
  if (!(output_resolution >= 0.0)) throw Error("accelerometer: output_resolution must not be negative");
  Unit::parse(output_unit);
}

nlohmann::json AccelerometerParameters::to_json() const {
  return {{"id", id},
          {"output_unit", output_unit},
          {"sample_rate_hz", sample_rate_hz},
          {"scale_factor", scale_factor},
          {"bias_g", bias_g},
          {"misalignment_arcsec", misalignment_arcsec},
          {"noise_ug_rt_hz", noise_ug_rt_hz},
          {"output_resolution", output_resolution}};
}

Vector3 AccelerometerParameters::input_axis() const {
  const double a = misalignment_arcsec[0] * constants::kArcsecond;
  const double b = misalignment_arcsec[1] * constants::kArcsecond;
  return {std::cos(a) * std::cos(b), std::sin(a) * std::cos(b), std::sin(b)};
}

AccelerometerModel::AccelerometerModel(const AccelerometerParameters& parameters, Random random)
    : parameters_(parameters), random_(random) {
  parameters_.validate();
  input_axis_ = parameters_.input_axis();
}

double AccelerometerModel::noise_free_output(const Vector3& f) const {
  return parameters_.scale_factor * (parameters_.bias_g + dot(input_axis_, f));
}

std::vector<double> AccelerometerModel::record(const Vector3& f, std::size_t samples) {
  // White noise of one-sided density n: the mean over one sample interval 1/fs has σ = n·√(fs/2).
  const double sigma = parameters_.noise_ug_rt_hz * 1e-6 * std::sqrt(parameters_.sample_rate_hz / 2.0);
  const double clean = noise_free_output(f);
  const double q = parameters_.output_resolution;
  std::vector<double> out(samples);
  for (auto& v : out) {
    v = clean + parameters_.scale_factor * sigma * random_.normal();
    if (q > 0.0) v = q * std::round(v / q);
  }
  return out;
}

}  // namespace inertest::sim

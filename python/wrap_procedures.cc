// procedures: the GJB 2426A-2004 / IEEE Std 952-1997 procedures on numpy arrays.
#include "bindings.h"
#include "inertest/procedures/bias.h"
#include "inertest/procedures/earth_rate.h"
#include "inertest/procedures/scale_factor.h"

namespace inertest::python {
namespace {

struct ScaleFactorTag {};

ResultOf<ScaleFactorTag> scale_factor_of(const DoubleArray& rate, const DoubleArray& output,
                                         const std::string& rate_unit, const std::string& output_unit,
                                         std::size_t recommended_rates_per_direction,
                                         const std::optional<std::string>& source) {
  const auto rates = as_span(rate, "rate");
  const auto outputs = as_span(output, "output");
  require_equal_lengths({{"rate", rates.size()}, {"output", outputs.size()}});
  std::vector<ScaleFactorPoint> points(rates.size());
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = {rates[i], outputs[i]};
  ScaleFactorOptions options;
  options.rate_unit = rate_unit;
  options.output_unit = output_unit;
  options.recommended_rates_per_direction = recommended_rates_per_direction;
  return make_result<ScaleFactorTag>(with_source(source, [&] { return scale_factor(points, options); }));
}

struct BiasTag {};

ResultOf<BiasTag> bias_of(const DoubleArray& output, double sample_rate_hz, std::optional<double> scale_factor,
                          bool input_in_deg_h, const std::string& output_unit, const std::vector<double>& smoothing_s,
                          bool random_walk, std::optional<double> latitude_deg, double heading_deg,
                          double elevation_deg, const std::optional<std::string>& source) {
  const auto samples = as_span(output, "output");
  BiasOptions options;
  options.sample_rate_hz = sample_rate_hz;
  options.scale_factor = scale_factor.value_or(0.0);
  options.input_in_deg_h = input_in_deg_h;
  options.output_unit = output_unit;
  options.smoothing_s = smoothing_s;
  options.random_walk = random_walk;
  if (latitude_deg) options.remove_earth_rate = AxisOrientation{*latitude_deg, heading_deg, elevation_deg};
  BiasResult result;
  {
    py::gil_scoped_release release;
    result = with_source(source, [&] { return bias(samples, options); });
  }
  return make_result<BiasTag>(result);
}

}  // namespace

void wrap_procedures(py::module_& module) {
  using namespace pybind11::literals;
  bind_result<ScaleFactorTag>(
      module, "ScaleFactorResult",
      "Scale factor result (GJB 2426A-2004 5.8.1-5.8.3, eqs. (1)-(11)). Members as in the JSON:\n"
      "scale_factor (K, eq. 5), zero_offset (F0, eq. 6), nonlinearity (Kn, eq. 9, ppm), asymmetry (Ka,\n"
      "eqs. 10-11, ppm), scale_factor_positive, scale_factor_negative, static_output_start,\n"
      "static_output_end, fit_residual_rms (Figures); nonlinearity_curve (list of Records with rate and\n"
      "deviation, eq. 8); warnings; procedure; clause.");
  module.def("scale_factor", &scale_factor_of, "rate"_a, "output"_a, py::kw_only(), "rate_unit"_a = "deg/s",
             "output_unit"_a = "1", "recommended_rates_per_direction"_a = 11, "source"_a = py::none(),
             "Scale factor K, zero offset F0, nonlinearity Kn and asymmetry Ka: GJB 2426A-2004 5.8.1-5.8.3,\n"
             "eqs. (1)-(11); IEEE Std 952-1997 clause 13 (A.12).\n"
             "rate: table rate of every test point in test order (signed, rate_unit); output: the mean\n"
             "instrument output at that rate (eq. 1, output_unit). Zero-rate points before the first and\n"
             "after the last nonzero rate are the static runs (eqs. 2-3); the nonzero rates are fitted by\n"
             "least squares F = K*Omega + F0 (eqs. 4-6). source names the input in error messages.\n"
             "Returns a ScaleFactorResult; raises inertest.Error (a ValueError) with the CLI's message.");

  bind_result<BiasTag>(
      module, "BiasResult",
      "Bias, bias stability and random walk coefficient (GJB 2426A-2004 5.12.1 eq. (19), 5.12.2 eq. (20),\n"
      "5.12.5.4.1 eqs. (23)-(24)). Members as in the JSON: bias (deg/h), bias_stability (one Record per\n"
      "smoothing time), noise_equivalent_rate, random_walk_coefficient (deg/sqrt(h)), ...");
  module.def("bias", &bias_of, "output"_a, py::kw_only(), "sample_rate_hz"_a, "scale_factor"_a = py::none(),
             "input_in_deg_h"_a = false, "output_unit"_a = "1",
             "smoothing_s"_a = std::vector<double>{1.0, 10.0, 100.0}, "random_walk"_a = true,
             "latitude_deg"_a = py::none(), "heading_deg"_a = 0.0, "elevation_deg"_a = 0.0, "source"_a = py::none(),
             "Bias B0 = F/K (GJB 2426A-2004 5.12.1 eq. (19)), bias stability over each smoothing time (5.12.2\n"
             "eq. (20)) and the random walk coefficient by normalisation (5.12.5.4.1 eqs. (23)-(24)); IEEE Std\n"
             "952-1997 clause 13 (A.11). output: one sample per interval at sample_rate_hz (read in place, no\n"
             "copy); scale_factor K in output units per deg/s, or input_in_deg_h=True for a record in deg/h.\n"
             "latitude_deg (with the IRA's heading_deg, elevation_deg) removes the Earth rate along the IRA.");
}

}  // namespace inertest::python

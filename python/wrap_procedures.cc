// procedures: the GJB 2426A-2004 / IEEE Std 952-1997 procedures on numpy arrays.
#include "bindings.h"
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
}

}  // namespace inertest::python

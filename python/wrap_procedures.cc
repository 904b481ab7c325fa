// procedures: the GJB 2426A-2004 / IEEE Std 952-1997 procedures on numpy arrays.
#include "bindings.h"

#include <limits>

#include "inertest/core/units.h"
#include "inertest/io/output_record.h"
#include "inertest/procedures/bandwidth_and_delay.h"
#include "inertest/procedures/bias.h"
#include "inertest/procedures/bias_repeatability.h"
#include "inertest/procedures/bias_temperature_sensitivity.h"
#include "inertest/procedures/earth_rate.h"
#include "inertest/procedures/hand_checks.h"
#include "inertest/procedures/input_axis_misalignment.h"
#include "inertest/procedures/maximum_input_rate.h"
#include "inertest/procedures/scale_factor.h"
#include "inertest/procedures/scale_factor_repeatability.h"
#include "inertest/procedures/threshold.h"

namespace inertest::python {
namespace {

// (rate, output) pairs as a procedure's point type (ScaleFactorPoint, RateTablePoint).
template <typename Point = ScaleFactorPoint>
std::vector<Point> points_of(const DoubleArray& rate, const DoubleArray& output) {
  const auto rates = as_span(rate, "rate");
  const auto outputs = as_span(output, "output");
  require_equal_lengths({{"rate", rates.size()}, {"output", outputs.size()}});
  std::vector<Point> points(rates.size());
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = {rates[i], outputs[i]};
  return points;
}

struct ScaleFactorTag {};

ResultOf<ScaleFactorTag> scale_factor_of(const DoubleArray& rate, const DoubleArray& output,
                                         const std::string& rate_unit, const std::string& output_unit,
                                         std::size_t recommended_rates_per_direction,
                                         const std::optional<std::string>& source) {
  ScaleFactorOptions options;
  options.rate_unit = rate_unit;
  options.output_unit = output_unit_as_rate(output_unit);
  options.recommended_rates_per_direction = recommended_rates_per_direction;
  // The arrays' own errors (a NaN, unequal lengths) name the source too.
  return make_spec_result<ScaleFactorTag>(
      scale_factor_spec(), with_source(source, [&] { return scale_factor(points_of(rate, output), options); }));
}

struct BiasTag {};

ResultOf<BiasTag> bias_of(const DoubleArray& output, double sample_rate_hz, std::optional<double> scale_factor,
                          bool input_in_deg_h, const std::string& output_unit, const std::vector<double>& smoothing_s,
                          bool random_walk, bool remove_earth_rate, std::optional<double> latitude_deg,
                          double heading_deg, double elevation_deg, const std::optional<std::string>& source) {
  std::span<const double> samples = with_source(source, [&] { return as_span(output, "output"); });
  BiasOptions options;
  options.sample_rate_hz = sample_rate_hz;
  options.scale_factor = scale_factor.value_or(0.0);
  options.input_in_deg_h = input_in_deg_h;
  options.output_unit = output_unit;
  options.smoothing_s = smoothing_s;
  options.random_walk = random_walk;
  // As the command line's --remove-earth-rate: a latitude alone removes nothing there, and removed the
  // Earth rate here (one record, biases 10.8 deg/h apart at 45.75 deg N); now it is refused alone, as
  // is the IRA's orientation.
  if (!remove_earth_rate && (latitude_deg || heading_deg != 0.0 || elevation_deg != 0.0)) {
    throw Error("bias: latitude_deg, heading_deg and elevation_deg are used only with remove_earth_rate=True (the "
                "command line's --latitude, --heading and --elevation with --remove-earth-rate)");
  }
  if (remove_earth_rate) {
    options.remove_earth_rate =
        AxisOrientation{latitude_deg.value_or(std::numeric_limits<double>::quiet_NaN()), heading_deg, elevation_deg};
  }
  // K and a record in deg/h exclude each other, as on the command line (K was silently ignored); the
  // output unit is one inertest reads, as there.
  ProcedureCall given;
  if (scale_factor) given.parameters["scale_factor"] = *scale_factor;
  given.parameters["output_unit"] = output_unit;
  given.pulse_counts = counts_pulses(output_unit);  // with input_in_deg_h an error
  check_bias_conversion(given, options, "bias");
  check_unit_parameters(given);
  std::vector<double> rates;  // pulses counted per sample interval as pulse/s (read_pulse_counts_as_rates)
  if (given.pulse_counts) {
    rates.assign(samples.begin(), samples.end());
    pulse_counts_as_rates(rates, sample_rate_hz);
    samples = rates;
    options.output_unit = output_unit_as_rate(output_unit);
  }
  BiasResult result;
  {
    py::gil_scoped_release release;
    result = with_source(source, [&] { return bias(samples, options); });
  }
  return make_spec_result<BiasTag>(bias_spec(), result);
}

struct MaximumInputRateTag {};

ResultOf<MaximumInputRateTag> maximum_input_rate_of(const DoubleArray& rate, const DoubleArray& output,
                                                    double nonlinearity_limit_ppm, const std::string& rate_unit,
                                                    const std::string& output_unit) {
  MaximumInputRateOptions options;
  options.nonlinearity_limit_ppm = nonlinearity_limit_ppm;
  options.scale_factor.rate_unit = rate_unit;
  options.scale_factor.output_unit = output_unit_as_rate(output_unit);
  return make_spec_result<MaximumInputRateTag>(maximum_input_rate_spec(),
                                               maximum_input_rate(points_of(rate, output), options));
}

struct ScaleFactorRepeatabilityTag {};

ResultOf<ScaleFactorRepeatabilityTag> scale_factor_repeatability_of(const DoubleArray& scale_factors,
                                                                    const std::string& unit,
                                                                    std::size_t minimum_runs) {
  ScaleFactorRepeatabilityOptions options;
  options.minimum_runs = minimum_runs;
  return make_spec_result<ScaleFactorRepeatabilityTag>(
      scale_factor_repeatability_spec(), scale_factor_repeatability(as_span(scale_factors, "scale_factors"), unit, options));
}

struct BiasRepeatabilityTag {};

ResultOf<BiasRepeatabilityTag> bias_repeatability_of(const DoubleArray& biases_deg_h) {
  return make_spec_result<BiasRepeatabilityTag>(bias_repeatability_spec(),
                                                bias_repeatability(as_span(biases_deg_h, "biases_deg_h")));
}

struct BiasTemperatureTag {};

ResultOf<BiasTemperatureTag> bias_temperature_sensitivity_of(const DoubleArray& temperature_degC,
                                                             const DoubleArray& bias_deg_h,
                                                             std::optional<double> room_temperature_degC) {
  const auto temperatures = as_span(temperature_degC, "temperature_degC");
  const auto biases = as_span(bias_deg_h, "bias_deg_h");
  require_equal_lengths({{"temperature_degC", temperatures.size()}, {"bias_deg_h", biases.size()}});
  std::vector<TemperatureRunBias> runs(temperatures.size());
  for (std::size_t i = 0; i < runs.size(); ++i) runs[i] = {temperatures[i], biases[i]};
  return make_spec_result<BiasTemperatureTag>(bias_temperature_spec(),
                                              bias_temperature_sensitivity(runs, BiasTemperatureOptions{room_temperature_degC}));
}

struct BandwidthTag {};

ResultOf<BandwidthTag> bandwidth_of(const DoubleArray& frequency_hz, const DoubleArray& gain,
                                    const DoubleArray& phase_deg, std::size_t minimum_frequencies) {
  const auto frequencies = as_span(frequency_hz, "frequency_hz");
  const auto gains = as_span(gain, "gain");
  const auto phases = as_span(phase_deg, "phase_deg");
  require_equal_lengths({{"frequency_hz", frequencies.size()}, {"gain", gains.size()}, {"phase_deg", phases.size()}});
  std::vector<FrequencyResponsePoint> points(frequencies.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i] = {frequencies[i], gains[i], phases[i] * constants::kDegree};
  }
  BandwidthOptions options;
  options.minimum_frequencies = minimum_frequencies;
  return make_spec_result<BandwidthTag>(bandwidth_spec(), bandwidth_and_delay(points, options));
}

struct ThresholdTag {};

ResultOf<ThresholdTag> threshold_rate_table_of(const DoubleArray& rate, const DoubleArray& output, double scale_factor,
                                               const std::string& rate_unit, std::optional<double> zero_output,
                                               const std::string& criterion_denominator) {
  ThresholdOptions options;
  options.scale_factor = scale_factor;
  options.rate_unit = rate_unit;
  options.zero_output = zero_output;
  options.criterion_denominator = parse_criterion_denominator(criterion_denominator);
  return make_spec_result<ThresholdTag>(threshold_spec(), threshold_rate_table(points_of<RateTablePoint>(rate, output), options));
}

struct InputAxisMisalignmentTag {};

ResultOf<InputAxisMisalignmentTag> input_axis_misalignment_of(const DoubleArray& output_positive,
                                                              const DoubleArray& output_negative, double scale_factor,
                                                              double rate, const std::string& rate_unit,
                                                              const std::string& output_unit) {
  const auto positive = as_span(output_positive, "output_positive");
  const auto negative = as_span(output_negative, "output_negative");
  require_equal_lengths({{"output_positive", positive.size()}, {"output_negative", negative.size()}});
  std::vector<MisalignmentPosition> positions(positive.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    positions[i].output_positive = positive[i];
    positions[i].output_negative = negative[i];
  }
  InputAxisMisalignmentOptions options;
  options.scale_factor = scale_factor;
  options.rate = rate;
  options.rate_unit = rate_unit;
  options.output_unit = output_unit_as_rate(output_unit);
  return make_spec_result<InputAxisMisalignmentTag>(input_axis_misalignment_spec(), input_axis_misalignment(positions, options));
}

struct HandChecksTag {};

// One check as a dict, as a plan's [[procedure.check]] table holds it: name, value (a number, or
// "pass" / "fail" for a check by eye), and optionally unit, min and max.
HandCheck hand_check_of(const py::dict& given) {
  HandCheck check;
  // A number that is no number (None, a bool, an array) was a pybind11 RuntimeError naming nothing.
  const auto number = [](const std::string& key, const py::handle& value) {
    if (!is_number(value)) {
      throw Error("hand check: '" + key + "' must be a number, not " + py::repr(value).cast<std::string>());
    }
    return py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
  };
  for (const auto& [key, value] : given) {
    const auto name = py::str(key).cast<std::string>();
    if (name == "name") {
      if (!py::isinstance<py::str>(value)) throw Error("hand check: 'name' must be a string");
      check.name = value.cast<std::string>();
    } else if (name == "value" && py::isinstance<py::str>(value)) {
      const auto verdict = value.cast<std::string>();
      if (verdict != "pass" && verdict != "fail") {
        throw Error("hand check value '" + verdict + "': a number, \"pass\" or \"fail\"");
      }
      check.verdict = verdict == "pass";
    } else if (name == "value") {
      check.value = number(name, value);
    } else if (name == "unit") {
      if (!py::isinstance<py::str>(value)) throw Error("hand check: 'unit' must be a string");
      check.unit = value.cast<std::string>();
    } else if (name == "min" || name == "max") {
      (name == "min" ? check.min : check.max) = number(name, value);
    } else {
      throw Error("hand check: unknown key '" + name + "' (name, value, unit, min, max)");
    }
  }
  return check;
}

ResultOf<HandChecksTag> hand_checks_of(const std::vector<py::dict>& given) {
  std::vector<HandCheck> checks;
  for (const py::dict& check : given) checks.push_back(hand_check_of(check));
  return make_result<HandChecksTag>(hand_checks(checks));
}

}  // namespace

void wrap_procedures(py::module_& module) {
  using namespace pybind11::literals;
  bind_result<ScaleFactorTag>(module, "ScaleFactorResult", result_doc(scale_factor_spec()));
  module.def("scale_factor", &scale_factor_of, "rate"_a, "output"_a, py::kw_only(), "rate_unit"_a = "deg/s",
             "output_unit"_a = "1", "recommended_rates_per_direction"_a = 11, "source"_a = py::none(),
             "Scale factor K, zero offset F0, nonlinearity Kn and asymmetry Ka: GJB 2426A-2004 5.8.1-5.8.3,\n"
             "eqs. (1)-(11); IEEE Std 952-1997 clause 13 (A.12).\n"
             "rate: table rate of every test point in test order (signed, rate_unit); output: the mean\n"
             "instrument output at that rate (eq. 1, output_unit). Zero-rate points before the first and\n"
             "after the last nonzero rate are the static runs (eqs. 2-3); the nonzero rates are fitted by\n"
             "least squares F = K*Omega + F0 (eqs. 4-6). source names the input in error messages.\n"
             "Returns a ScaleFactorResult; raises inertest.Error (a ValueError) with the CLI's message.");

  bind_result<HandChecksTag>(
      module, "HandChecksResult",
      "Checks measured by hand (GJB 2426A-2004 5.2-5.4): members as in the CLI's --json object, and\n"
      "one Figure per check under the snake_case of its name (e.g. insulation_resistance).\n"
      "Members:\n"
      "    procedure: str\n"
      "    clause: str\n"
      "    check_pass: Record  # by check key: whether it is within its min and max (a max alone: |value| <= max)\n"
      "    checks: list[Record]  # key, name, value, unit, min, max, pass\n"
      "    all_pass: bool\n");
  module.def("hand_checks", &hand_checks_of, "checks"_a,
             "Checks measured by hand (GJB 2426A-2004 5.2 appearance, 5.3 insulation resistance, impedance,\n"
             "dielectric strength, 5.4 power per supply), as the plan kind hand_checks takes them: checks is a\n"
             "list of dicts with name, value (a number, or 'pass' / 'fail' for appearance) and optionally unit,\n"
             "min and max, e.g. {'name': 'Insulation resistance', 'value': 120, 'unit': 'Mohm', 'min': 20}.");

  bind_result<BiasTag>(module, "BiasResult", result_doc(bias_spec()));
  module.def("bias", &bias_of, "output"_a, py::kw_only(), "sample_rate_hz"_a, "scale_factor"_a = py::none(),
             "input_in_deg_h"_a = false, "output_unit"_a = "1",
             "smoothing_s"_a = std::vector<double>{1.0, 10.0, 100.0}, "random_walk"_a = true,
             "remove_earth_rate"_a = false, "latitude_deg"_a = py::none(), "heading_deg"_a = 0.0,
             "elevation_deg"_a = 0.0, "source"_a = py::none(),
             "Bias B0 = F/K (GJB 2426A-2004 5.12.1 eq. (19)), bias stability over each smoothing time (5.12.2\n"
             "eq. (20)) and the random walk coefficient by normalisation (5.12.5.4.1 eqs. (23)-(24)); IEEE Std\n"
             "952-1997 clause 13 (A.11). output: one sample per interval at sample_rate_hz (read in place, no\n"
             "copy); scale_factor K in output units per deg/s, or input_in_deg_h=True for a record in deg/h.\n"
             "remove_earth_rate=True removes the Earth rate along the IRA at latitude_deg (with the IRA's\n"
             "heading_deg, elevation_deg), as the command line's --remove-earth-rate --latitude.");

  bind_result<MaximumInputRateTag>(module, "MaximumInputRateResult", result_doc(maximum_input_rate_spec()));
  module.def("maximum_input_rate", &maximum_input_rate_of, "rate"_a, "output"_a, py::kw_only(),
             "nonlinearity_limit_ppm"_a, "rate_unit"_a = "deg/s", "output_unit"_a = "1",
             "Maximum input rate (GJB 2426A-2004 5.9): the largest tested rate R such that the scale-factor\n"
             "nonlinearity (eqs. 1-9) over the points with |rate| <= R meets nonlinearity_limit_ppm. rate and\n"
             "output as for scale_factor().");

  bind_result<ScaleFactorRepeatabilityTag>(module, "ScaleFactorRepeatabilityResult",
                                           result_doc(scale_factor_repeatability_spec()));
  module.def("scale_factor_repeatability", &scale_factor_repeatability_of, "scale_factors"_a, py::kw_only(),
             "unit"_a = "1", "minimum_runs"_a = 6,
             "Scale factor repeatability Kr (GJB 2426A-2004 5.8.4, eq. (12)): the sample standard deviation of\n"
             "the runs' scale factors over their mean, in ppm. Q >= 6 runs (5.8.4.3); minimum_runs lowers that\n"
             "with a warning.");

  bind_result<BiasRepeatabilityTag>(module, "BiasRepeatabilityResult", result_doc(bias_repeatability_spec()));
  module.def("bias_repeatability", &bias_repeatability_of, "biases_deg_h"_a,
             "Bias repeatability Br (GJB 2426A-2004 5.12.3, eq. (21)): the sample standard deviation of the runs'\n"
             "biases B0i (deg/h), each from bias().");

  bind_result<BiasTemperatureTag>(module, "BiasTemperatureSensitivityResult", result_doc(bias_temperature_spec()));
  module.def("bias_temperature_sensitivity", &bias_temperature_sensitivity_of, "temperature_degC"_a, "bias_deg_h"_a,
             py::kw_only(), "room_temperature_degC"_a = py::none(),
             "Bias temperature sensitivity Bt (GJB 2426A-2004 5.12.4, eq. (22)): max |B0i - B0m| / |Ti - Tm| over\n"
             "the runs, in deg/h/degC; the room-temperature run is the first, or the one at room_temperature_degC.");

  bind_result<BandwidthTag>(module, "BandwidthResult", result_doc(bandwidth_spec()));
  module.def("bandwidth_and_delay", &bandwidth_of, "frequency_hz"_a, "gain"_a, "phase_deg"_a, py::kw_only(),
             "minimum_frequencies"_a = 10,
             "Bandwidth (GJB 2426A-2004 5.13, eqs. (32)-(41)) and output delay (5.14, eqs. (42)-(46)) from the\n"
             "gain Gi and the phase Pi of the output against the input rate (deg, negative for a lag) at >= 10\n"
             "increasing frequencies: linearised least squares Gi^2 = K^2 - Gi^2 wi^2 T^2, Bw = 1/(2 pi T),\n"
             "Td from -Pi - atan(wi T) with wi = 2 pi fi; a phase beyond +-90 deg at the lowest frequency is a\n"
             "negative scale factor, whose 180 deg is removed from every phase first (polarity = -1).");

  bind_result<ThresholdTag>(module, "ThresholdResult", result_doc(threshold_spec()));
  module.def("threshold_rate_table", &threshold_rate_table_of, "rate"_a, "output"_a, py::kw_only(), "scale_factor"_a,
             "rate_unit"_a = "deg/s", "zero_output"_a = py::none(), "criterion_denominator"_a = "expected",
             "Threshold by method 1 (GJB 2426A-2004 5.10.4.1, rate table): the mean output at each signed table\n"
             "rate; K in output units per deg/s; zero-rate points give the zero output unless zero_output. An\n"
             "input passes while |F_expected - F| <= 50 % of F_expected ('expected', IEEE Std 952-1997, as eq. 18)\n"
             "or of the measured F ('measured', eq. (15) as printed, a 67 % criterion).");

  bind_result<InputAxisMisalignmentTag>(module, "InputAxisMisalignmentResult",
                                        result_doc(input_axis_misalignment_spec()));
  module.def("input_axis_misalignment", &input_axis_misalignment_of, "output_positive"_a, "output_negative"_a,
             py::kw_only(), "scale_factor"_a, "rate"_a, "rate_unit"_a = "deg/s", "output_unit"_a = "1",
             "Input-axis misalignment (GJB 2426A-2004 5.15, eqs. (47)-(50)) from the mean outputs at +rate and\n"
             "-rate in 2 or 4 positions: delta = (F+ - F-)/(2 K rate) with K output per deg/s whatever rate_unit\n"
             "is (the dimension fix of eqs. 47-48); with four positions the mounting error is separated (see the\n"
             "C++ header).");
}

}  // namespace inertest::python

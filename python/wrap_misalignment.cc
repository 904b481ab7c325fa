// misalignment: separation of an instrument's input-axis misalignment from the table's and the
// fixture's errors (the misalignment paper, cited in core/citations.h).

#include <array>
#include <cmath>

#include <fmt/format.h>

#include "bindings.h"
#include "inertest/io/output_record.h"
#include "inertest/misalignment/accelerometer_misalignment.h"
#include "inertest/misalignment/gyro_misalignment.h"
#include "inertest/misalignment/misalignment_files.h"
#include "inertest/misalignment/revolution_average.h"

namespace inertest::python {
namespace {

// Whole numbers given as any numeric array: each must be one, at least `least` (numpy's own cast
// to an integer type took 1.5 for 1, NaN for -2^63 and -1 for a line 2^64 - 1).
template <typename Integer>
std::vector<Integer> whole_numbers(const DoubleArray& given, const char* name, double least, std::size_t rows) {
  const auto values = as_span(given, name);
  require_equal_lengths({{"output", rows}, {name, values.size()}});
  std::vector<Integer> whole(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!(values[i] >= least) || values[i] != std::floor(values[i]) || values[i] > 9.0e15) {
      throw Error(fmt::format("{}: value {} ({}) is not a whole number of at least {}", name, i + 1, values[i], least));
    }
    whole[i] = static_cast<Integer>(values[i]);
  }
  return whole;
}

struct GyroMisalignmentTag {};
struct AccelerometerMisalignmentTag {};

// The 1-based input line of every row, or none.
std::vector<std::size_t> lines_of(const std::optional<DoubleArray>& line, std::size_t rows) {
  return line ? whole_numbers<std::size_t>(*line, "line", 0.0, rows) : std::vector<std::size_t>(rows, 0);
}

ResultOf<GyroMisalignmentTag> gyro_misalignment_of(const DoubleArray& alpha_deg, const DoubleArray& beta_deg,
                                                   const DoubleArray& rate_dps, const DoubleArray& output,
                                                   double scale_factor, const std::string& output_unit,
                                                   const std::optional<DoubleArray>& line,
                                                   const std::optional<std::string>& source) {
  const auto alpha = as_span(alpha_deg, "alpha_deg");
  const auto beta = as_span(beta_deg, "beta_deg");
  const auto rate = as_span(rate_dps, "rate_dps");
  const auto outputs = as_span(output, "output");
  require_equal_lengths({{"output", outputs.size()},
                         {"alpha_deg", alpha.size()},
                         {"beta_deg", beta.size()},
                         {"rate_dps", rate.size()}});
  const std::vector<std::size_t> lines = lines_of(line, outputs.size());
  GyroMisalignmentOptions options;
  options.scale_factor = scale_factor;
  options.output_unit = output_unit_as_rate(output_unit);
  options.source = source.value_or("");
  options.validate();
  std::vector<GyroMisalignmentRow> rows(outputs.size());
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = {alpha[i], beta[i], rate[i], outputs[i], lines[i]};
  return make_spec_result<GyroMisalignmentTag>(gyro_misalignment_spec(), gyro_misalignment(rows, options));
}

ResultOf<AccelerometerMisalignmentTag> accelerometer_misalignment_of(
    const DoubleArray& beta_deg, const DoubleArray& output, double scale_factor, const std::optional<DoubleArray>& run,
    const std::string& output_unit, const std::optional<DoubleArray>& line, const std::optional<std::string>& source) {
  const auto beta = as_span(beta_deg, "beta_deg");
  const auto outputs = as_span(output, "output");
  require_equal_lengths({{"output", outputs.size()}, {"beta_deg", beta.size()}});
  const std::vector<long> runs = run ? whole_numbers<long>(*run, "run", -9.0e15, outputs.size())
                                     : std::vector<long>(outputs.size(), 1);
  const std::vector<std::size_t> lines = lines_of(line, outputs.size());
  AccelerometerMisalignmentOptions options;
  options.scale_factor = scale_factor;
  options.output_unit = output_unit_as_rate(output_unit);
  options.source = source.value_or("");
  options.validate();
  std::vector<AccelerometerMisalignmentRow> rows(outputs.size());
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = {beta[i], outputs[i], runs[i], lines[i]};
  return make_spec_result<AccelerometerMisalignmentTag>(accelerometer_misalignment_spec(),
                                                        accelerometer_misalignment(rows, options));
}

// The rows as keyword arguments of gyro_misalignment: column arrays, line and source.
py::dict gyro_rows_as_arguments(const std::vector<GyroMisalignmentRow>& rows, const std::string& source) {
  std::vector<double> alpha, beta, rate, output;
  std::vector<std::size_t> line;
  for (const auto& row : rows) {
    alpha.push_back(row.alpha_deg);
    beta.push_back(row.beta_deg);
    rate.push_back(row.rate_dps);
    output.push_back(row.output);
    line.push_back(row.line);
  }
  py::dict arguments;
  arguments["alpha_deg"] = to_numpy(std::move(alpha));
  arguments["beta_deg"] = to_numpy(std::move(beta));
  arguments["rate_dps"] = to_numpy(std::move(rate));
  arguments["output"] = to_numpy(std::move(output));
  arguments["line"] = to_numpy(std::move(line));
  arguments["source"] = source;
  return arguments;
}

py::dict accelerometer_rows_as_arguments(const std::vector<AccelerometerMisalignmentRow>& rows,
                                         const std::string& source) {
  std::vector<double> beta, output;
  std::vector<long> run;
  std::vector<std::size_t> line;
  for (const auto& row : rows) {
    beta.push_back(row.beta_deg);
    output.push_back(row.output);
    run.push_back(row.run);
    line.push_back(row.line);
  }
  py::dict arguments;
  arguments["beta_deg"] = to_numpy(std::move(beta));
  arguments["output"] = to_numpy(std::move(output));
  arguments["run"] = to_numpy(std::move(run));
  arguments["line"] = to_numpy(std::move(line));
  arguments["source"] = source;
  return arguments;
}

Record revolution_mean_record(const RevolutionMean& mean) {
  return Record(
      {{"mean", mean.mean}, {"revolutions", mean.revolutions}, {"samples_used", mean.samples_used}});
}

}  // namespace

void wrap_misalignment(py::module_& module) {
  using namespace pybind11::literals;
  bind_result<GyroMisalignmentTag>(module, "GyroMisalignmentResult", result_doc(gyro_misalignment_spec()));
  bind_result<AccelerometerMisalignmentTag>(module, "AccelerometerMisalignmentResult",
                                            result_doc(accelerometer_misalignment_spec()));

  module.def("gyro_misalignment", &gyro_misalignment_of, "alpha_deg"_a, "beta_deg"_a, "rate_dps"_a, "output"_a,
             py::kw_only(), "scale_factor"_a, "output_unit"_a = "1", "line"_a = py::none(), "source"_a = py::none(),
             "Separates the gyro's input-axis misalignment (dy2, dz2) from the table's (dy0, dx0) and the\n"
             "fixture's (dy1) errors (the misalignment paper, eq. for w_I): least squares\n"
             "on V(+) - V(-) = 2 kI w (-dy0 cos b + dx0 sin b - dy1 + dz2 sin a - dy2 cos a), at every rate and\n"
             "over all rates together. One row per position and direction: alpha_deg, beta_deg, rate_dps\n"
             "(signed: the direction), output averaged over whole revolutions. scale_factor: kI in output\n"
             "units per deg/s. line and source locate rows in error messages (the readers return them).\n"
             "Angles in arcsec. Raises inertest.Error (a ValueError) with the CLI's message.");
  module.def("accelerometer_misalignment", &accelerometer_misalignment_of, "beta_deg"_a, "output"_a, py::kw_only(),
             "scale_factor"_a, "run"_a = py::none(), "output_unit"_a = "1", "line"_a = py::none(),
             "source"_a = py::none(),
             "Accelerometer input-axis misalignment dy2, dz2 by the multi-position gravity test (the misalignment\n"
             "paper): least squares on V = V0 + kI(-dy0 - dy1 + dz2 sin b - dy2 cos b)\n"
             "run by run, combined by the mean over runs. scale_factor: kI in output units per g. run: the\n"
             "run of every row (all run 1 when None). Angles in arcsec.");

  module.def(
      "read_gyro_misalignment_positions",
      [](const std::filesystem::path& path) {
        return gyro_rows_as_arguments(read_gyro_misalignment_positions(path.string()), path.string());
      },
      "path"_a,
      "Reads a gyro misalignment means CSV (header alpha_deg,beta_deg,rate_dps,output) as the keyword\n"
      "arguments of gyro_misalignment: {'alpha_deg', 'beta_deg', 'rate_dps', 'output': arrays, 'line':\n"
      "1-based lines, 'source': path}; gyro_misalignment(**rows, scale_factor=k) does what the CLI does.");
  module.def(
      "read_gyro_misalignment_records",
      [](const std::filesystem::path& listing_path, bool pulse_counts) {
        return gyro_rows_as_arguments(read_gyro_misalignment_records(listing_path.string(), pulse_counts),
                                      listing_path.string());
      },
      "listing_path"_a, py::kw_only(), "pulse_counts"_a = false,
      "Reads a listing CSV (header alpha_deg,beta_deg,rate_dps,file) of raw records, each averaged over\n"
      "whole revolutions (by table_angle_deg or time_s), as the keyword arguments of gyro_misalignment\n"
      "(the CLI's --records). pulse_counts=True: the outputs count pulses per sample interval, and each\n"
      "mean is times its record's sample rate (time_s needed), pulse/s, as output_unit='pulse' on the CLI.");
  module.def(
      "read_accelerometer_misalignment_positions",
      [](const std::filesystem::path& path) {
        return accelerometer_rows_as_arguments(read_accelerometer_misalignment_positions(path.string()), path.string());
      },
      "path"_a,
      "Reads an accelerometer positions CSV (header beta_deg,output and optionally run) as the keyword\n"
      "arguments of accelerometer_misalignment.");

  module.def(
      "whole_revolution_mean_by_angle",
      [](const DoubleArray& table_angle_deg, const DoubleArray& output) {
        const auto angle = as_span(table_angle_deg, "table_angle_deg");
        const auto outputs = as_span(output, "output");
        require_equal_lengths({{"table_angle_deg", angle.size()}, {"output", outputs.size()}});
        return revolution_mean_record(whole_revolution_mean_by_angle(angle, outputs));
      },
      "table_angle_deg"_a, "output"_a,
      "Mean output over the whole table revolutions at the start of a record, cut by the (unwrapped)\n"
      "table angle, so that the Earth-rate terms of the misalignment paper's w_I average to zero. Returns a Record\n"
      "with mean, revolutions and samples_used. The arrays are read in place (no copy).");
  module.def(
      "whole_revolution_mean_by_time",
      [](const DoubleArray& time_s, const DoubleArray& output, double rate_dps) {
        const auto time = as_span(time_s, "time_s");
        const auto outputs = as_span(output, "output");
        require_equal_lengths({{"time_s", time.size()}, {"output", outputs.size()}});
        return revolution_mean_record(whole_revolution_mean_by_time(time, outputs, rate_dps));
      },
      "time_s"_a, "output"_a, "rate_dps"_a,
      "Mean output over the whole table revolutions at the start of a record, cut by time and the table\n"
      "rate (deg/s). Returns a Record with mean, revolutions and samples_used.");

  module.def("four_position_misalignment", &four_position_misalignment, "v_0"_a, "v_90"_a, "v_180"_a, "v_270"_a,
             "scale_factor"_a,
             "The closed forms of the misalignment paper: (dy2, dz2) in rad = ((V(pi) - V(0)) / (2 kI),\n"
             "(V(pi/2) - V(3pi/2)) / (2 kI)); kI in output units per g.");
  module.def(
      "five_position_misalignment",
      [](const std::array<double, 5>& plus, const std::array<double, 5>& minus, double scale_factor, double rate_dps) {
        return five_position_misalignment(FivePositionOutputs{plus, minus}, scale_factor, rate_dps);
      },
      "plus"_a, "minus"_a, "scale_factor"_a, "rate_dps"_a,
      "The five-position closed forms of the misalignment paper (inertest.CITATIONS['misalignment']):\n"
      "outputs V1..V5\n"
      "at +w (plus) and -w (minus) at positions (alpha, beta) = (0,0), (0,180), (180,180), (90,180),\n"
      "(0,90) deg; returns (dy0, dx0, dy1, dy2, dz2) in rad. kI in output units per deg/s, w in deg/s.");
}

}  // namespace inertest::python

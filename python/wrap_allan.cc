// allan: the Allan-family deviations with confidence bounds and the noise-term fit (GJB 2426A-2004
// 5.12.5.4.2 eqs. (30)-(31), IEEE Std 952-1997 Annex C, NIST SP 1065).
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <variant>

#include "bindings.h"
#include "inertest/allan/allan.h"
#include "inertest/allan/allan_channels.h"
#include "inertest/allan/filter_parameters.h"
#include "inertest/allan/tau_grid.h"
#include "inertest/io/atomic_write.h"
#include "inertest/io/text_table.h"

namespace inertest::python {
namespace {

struct AllanTag {};
struct AllanChannelsTag {};

// The CLI's --export FORMAT FILE: (format, path).
using ExportArgument = std::optional<std::pair<std::string, std::filesystem::path>>;

void export_filter_parameters(const AllanChannels& channels, const ExportArgument& target, const std::string& command) {
  if (!target) return;
  write_file_atomically(target->second.string(), format_filter_parameters(filter_noise_parameters(channels),
                                                                 parse_filter_format(target->first), command));
}

// `taus` as Python gives it: a grid specification (str), or taus in seconds (a list or a numpy
// array, as allantools takes them), which become an explicit TauGrid (each tau must be a whole
// number of sample intervals, tau_grid.h).
using Taus = std::variant<std::string, std::vector<double>>;

std::string tau_specification(const Taus& taus) {
  if (const auto* text = std::get_if<std::string>(&taus)) return *text;
  TauGrid grid;
  grid.kind = TauGrid::Kind::kExplicit;
  grid.taus_s = std::get<std::vector<double>>(taus);
  return grid.to_string();
}

using FitRangeArgument = std::optional<std::pair<double, double>>;

std::optional<FitRange> fit_range_of(const FitRangeArgument& range) {
  if (!range) return std::nullopt;
  return FitRange{range->first, range->second};
}

// psd: None, or the Welch window ('hann', ...) and segment length (0: automatic).
using PsdArgument = std::optional<std::pair<std::string, std::size_t>>;

AllanOptions allan_options(double sample_rate_hz, const std::string& input_unit, const Taus& taus,
                           const std::string& estimators, double scale, double confidence, std::size_t worker_count,
                           const FitRangeArgument& fit_range, const PsdArgument& psd) {
  AllanOptions options;
  if (psd) {
    WelchOptions welch;
    welch.window = parse_spectral_window(psd->first);
    welch.segment_length = psd->second;
    options.psd = welch;
  }
  options.fit_range = fit_range_of(fit_range);
  options.sample_rate_hz = sample_rate_hz;
  options.input_unit = input_unit;
  options.taus = tau_specification(taus);
  options.estimators = EstimatorSet::parse(estimators);
  options.scale = scale;
  options.confidence = confidence;
  options.worker_count = worker_count;
  return options;
}

RateRecordSource rate_source(const std::string& path, const std::string& format, const std::optional<std::string>& column) {
  RateRecordSource source;
  source.path = path;
  source.set_format(format);
  if (column) source.column = ColumnSelector::parse(*column);
  return source;
}

// A 1-D array is one channel (AllanResult); a 2-D array holds one channel per column
// (AllanChannelsResult, named by `channels` or "1", "2", ...; input_unit as the CLI's --input-unit).
std::variant<ResultOf<AllanTag>, ResultOf<AllanChannelsTag>> allan_of_samples(
    const StridedDoubleArray& rate, double sample_rate_hz, const std::string& input_unit, const Taus& taus,
    const std::string& estimators, double scale, double confidence, std::size_t worker_count,
    const FitRangeArgument& fit_range, const std::optional<std::vector<std::string>>& channels,
    const ExportArgument& export_to, const PsdArgument& psd) {
  const AllanOptions common =
      allan_options(sample_rate_hz, "deg/h", taus, estimators, scale, confidence, worker_count, fit_range, psd);
  AllanChannels result;
  if (rate.ndim() == 1) {
    AllanOptions options = common;
    options.input_unit = input_unit;
    const DoubleArray contiguous = DoubleArray::ensure(rate);  // a strided view (a[:, 0]) copied once
    const auto samples = as_span(contiguous, "rate");
    {
      py::gil_scoped_release release;
      result.channels.push_back({channels && !channels->empty() ? channels->front() : "rate",
                                 allan_variance(samples, options)});
    }
    export_filter_parameters(result, export_to, "inertest.allan_variance");
    return make_result<AllanTag>(result.channels.front().result);
  }
  if (rate.ndim() != 2) throw Error(fmt::format("rate must be a 1-D or 2-D array, not {}-D", rate.ndim()));
  const auto rows = static_cast<std::size_t>(rate.shape(0));
  const auto count = static_cast<std::size_t>(rate.shape(1));
  if (count > rows) {
    throw Error(fmt::format("rate has {} rows and {} columns: the channels are the columns, one sample a row "
                            "(a transposed array? rate.T)", rows, count));
  }
  std::vector<std::string> names;
  for (std::size_t c = 0; c < count; ++c) names.push_back(std::to_string(c + 1));
  const std::vector<std::string> selectors = names;
  if (channels) {
    if (channels->size() != count) {
      throw Error(fmt::format("channels names {} channels but rate has {} columns", channels->size(), count));
    }
    names = *channels;
  }
  // The columns of a Fortran-ordered array (pandas' to_numpy()) are read where they are; those of
  // any other layout are strided, and each is copied once.
  std::vector<std::vector<double>> copies;
  std::vector<std::span<const double>> columns;
  if (rate.flags() & py::array::f_style) {
    for (std::size_t c = 0; c < count; ++c) columns.emplace_back(rate.data() + c * rows, rows);
  } else {
    copies.assign(count, std::vector<double>(rows));
    const auto view = rate.unchecked<2>();
    for (std::size_t r = 0; r < rows; ++r) {
      for (std::size_t c = 0; c < count; ++c) copies[c][r] = view(r, c);
    }
    columns.assign(copies.begin(), copies.end());
  }
  const std::vector<AllanOptions> options = channel_options(common, names, selectors, input_unit);
  {
    py::gil_scoped_release release;
    result = allan_variance_of_channels(columns, names, options);
  }
  export_filter_parameters(result, export_to, "inertest.allan_variance");
  return ResultOf<AllanChannelsTag>(result.to_json(), result.report());
}

}  // namespace

void wrap_allan(py::module_& module) {
  using namespace pybind11::literals;
  bind_result<AllanTag>(
      module, "AllanResult",
      "Allan analysis (GJB 2426A-2004 5.12.5.4.2, IEEE Std 952-1997 Annex C, NIST SP 1065): members as in\n"
      "the CLI's --json object.\n"
      "Members:\n"
      "    procedure: str\n"
      "    clause: str\n"
      "    standard: str\n"
      "    sample_count: int\n"
      "    sample_rate_hz: float\n"
      "    record_length: Figure  # s\n"
      "    input_unit: str\n"
      "    mean: Figure\n"
      "    tau_grid: str\n"
      "    confidence_level: float\n"
      "    tau: FloatArray  # s\n"
      "    averaging_factor: IntArray\n"
      "    noise_type: list[str]  # per tau, the dominant noise of the Allan variance (NIST SP 1065 5.6)\n"
      "    alpha: IntArray  # S_y(f) ~ f^alpha: 2 white PM, 1 flicker PM, 0 white FM, -1 flicker FM, -2 RW FM\n"
      "    # One Record per estimator asked for: unit, the numpy arrays values, lower, upper (the bounds),\n"
      "    # edf, terms, alpha (per tau, the noise its edf assumes), the lists noise_type and\n"
      "    # noise_identification ('lag1_autocorrelation', 'b1_ratio', 'b1_ratio_and_rn', 'shorter_tau',\n"
      "    # 'not_identified').\n"
      "    adev: Record\n"
      "    oadev: Record\n"
      "    mdev: Record\n"
      "    hdev: Record\n"
      "    ohdev: Record\n"
      "    totdev: Record\n"
      "    # quantization, angle_random_walk (= random_walk_coefficient, GJB eq. 31), bias_instability,\n"
      "    # rate_random_walk, rate_ramp (Figures; identified False with an upper_bound when not measured,\n"
      "    # significant False with one when measured within 2 sigma of zero),\n"
      "    # fit (GJB eq. 30: coefficients, reduced_chi_squared, verdict, fit_range), slope_method.\n"
      "    noise: Optional[Record]  # None when not fitted\n"
      "    psd: Record  # only with psd=: the Welch PSD (band means), noise_terms, peaks (periodic components)\n"
      "    warnings: list[str]\n");
  bind_result<AllanChannelsTag>(
      module, "AllanChannelsResult",
      "Allan analysis of several channels of one record (an IMU's axes), each as AllanResult; a channel in an\n"
      "acceleration unit has velocity_random_walk, bias_instability (ug) and acceleration_random_walk.\n"
      "Members:\n"
      "    procedure: str\n"
      "    clause: str\n"
      "    channels: Record  # one AllanResult-shaped Record per channel, by name\n");
  const char* options_doc =
      "sample_rate_hz: the record's sample rate; scale: a factor the samples are multiplied by (not the\n"
      "scale factor K, which allan(scale_factor=) and the CLI's --scale-factor divide by: give 1/K here);\n"
      "input_unit: unit of the samples after `scale` (deg/h);\n"
      "taus: 'octave', 'decade', 'all', 'N/decade', a comma list of tau in s, or a list or numpy array of tau\n"
      "in s (each a whole number of sample intervals to 1e-6, else an error; taus beyond the record are left\n"
      "out; the noise terms are fitted on the taus an octave or more apart); estimators: 'all' or a comma\n"
      "list of adev, oadev, mdev, hdev, ohdev, totdev; confidence: of the chi-squared bounds (1 sigma).\n"
      "Noise terms by the weighted fit of sigma^2 = sum A_p tau^p (GJB eq. 30; RWC = N, eq. 31) and by\n"
      "slope read-off; fit_range: (tau_min, tau_max) in s of that fit, None: chosen automatically (the\n"
      "result's noise.fit.fit_range says which and why). Raises inertest.Error (a ValueError) with the CLI's message.";
  module.def("allan_variance", &allan_of_samples, "rate"_a, py::kw_only(), "sample_rate_hz"_a,
             "input_unit"_a = "deg/h", "taus"_a = "octave", "estimators"_a = "all", "scale"_a = 1.0,
             "confidence"_a = kOneSigmaConfidence, "worker_count"_a = 2, "fit_range"_a = py::none(),
             "channels"_a = py::none(), "export"_a = py::none(), "psd"_a = py::none(),
             (std::string("Allan deviations ADEV, OADEV, MDEV, HDEV, OHDEV, TOTDEV of rate samples in memory (read in\n"
                          "place, no copy) with chi-squared bounds, and the noise terms Q, N, B, K, R.\n"
                          "A 2-D array holds one channel per column (an IMU's axes; Fortran-ordered, as pandas' to_numpy()\n"
                          "gives, its columns are read in place, other layouts are copied once): the result is an\n"
                          "AllanChannelsResult, its channels named by `channels` (default '1', '2', ...) and input_unit\n"
                          "as the CLI's --input-unit ('deg/s,ax=m/s^2'). export: (format, path), format 'kalibr',\n"
                          "'matlab', 'gnss-ins-sim' or 'json': the filter parameters, as the CLI's --export. psd: (window,\n"
                          "segment_length), e.g. ('hann', 0) for automatic segments: the Welch PSD beside the Allan\n"
                          "variance, its noise terms and periodic components (the result's psd), as --psd.\n") +
              options_doc)
                 .c_str());
  // The plan kind's function, inertest.allan (made from its spec by wrap_specs), under the name the
  // README gives it; the keywords are the spec's (the plan keys).
  module.def(
      "allan_variance_of_file",
      [](const std::filesystem::path& path, py::kwargs keywords) {
        keywords["file"] = path.string();
        return py::module_::import("inertest").attr("allan")(**keywords);
      },
      "path"_a,
      "inertest.allan(file=path, **keywords): the Allan analysis of a record streamed from a file (never held\n"
      "whole), as the CLI's allan command and the plan kind \"allan\" make it, with their parameters as keywords\n"
      "(sample_rate_hz, format, column, columns, input_unit, taus, scale_factor, estimators, fit_range,\n"
      "psd, psd_window, psd_segment_length, threads, export); see help(inertest.allan).");
  module.def(
      "read_rate_record",
      [](const std::filesystem::path& path, const std::string& format, const std::optional<std::string>& column) {
        const RateRecordSource source = rate_source(path.string(), format, column);
        std::vector<double> samples;
        {
          py::gil_scoped_release release;
          read_rate_record(source, [&](std::span<const double> chunk) { samples.insert(samples.end(), chunk.begin(), chunk.end()); });
        }
        return to_numpy(std::move(samples));
      },
      "path"_a, "format"_a = "auto", "column"_a = py::none(),
      "Reads one channel of a rate record (text; raw binary 'f64', 'f32', 'i32' or 'i16', optionally with 'le'\n"
      "or 'be'; or a channel of a .mat, HDF5 or TDMS record, by name as 'group/channel' or 'struct.field')\n"
      "into a float64 array that owns the buffer.\n"
      "Raises inertest.Error with file:line:column (or channel and sample) for a bad sample.");
  module.def(
      "fit_noise_terms",
      [](const DoubleArray& tau_s, const DoubleArray& variance, const DoubleArray& edf, const std::string& input_unit,
         const FitRangeArgument& fit_range, std::size_t sample_count, double sample_interval_s) {
        NoiseFitOptions options;
        options.fit_range = fit_range_of(fit_range);
        options.sample_count = sample_count;
        options.sample_interval_s = sample_interval_s;
        return Record(fit_noise_terms(as_span(tau_s, "tau_s"), as_span(variance, "variance"), as_span(edf, "edf"),
                                      input_unit, options)
                          .to_json(input_unit));
      },
      "tau_s"_a, "variance"_a, "edf"_a, "input_unit"_a = "deg/h", py::kw_only(), "fit_range"_a = py::none(),
      "sample_count"_a = 0, "sample_interval_s"_a = 0.0,
      "Noise terms from an Allan variance: non-negative generalised least squares of\n"
      "sigma^2(tau) = sum_{p=-2..2} A_p tau^p (GJB 2426A-2004 eq. (30)), the covariance of the overlapping\n"
      "estimates from the fitted model, then Q, N (= RWC, eq. 31), B, K, R by IEEE Std 952-1997 C.1 Table C.1.\n"
      "fit_range: (tau_min, tau_max) in s, None: chosen automatically; sample_count and sample_interval_s of\n"
      "the record (0: unknown; the interval is then the shortest tau). Returns a Record: Figures with 1-sigma\n"
      "uncertainties (significant False and upper_bound within 2 sigma of zero), or identified False and\n"
      "upper_bound; fit holds reduced_chi_squared, verdict, fit_range. One fit on the edf given: allan_variance's\n"
      "noise fits twice, on the taus an octave or more apart, the second time on the edf of the noise its first\n"
      "fit says dominates at each tau, so its result.noise differs from one call on result.oadev's edf.");
  module.def(
      "read_noise_slopes",
      [](const DoubleArray& tau_s, const DoubleArray& deviation, const DoubleArray& edf, const std::string& input_unit) {
        return Record(read_noise_slopes(as_span(tau_s, "tau_s"), as_span(deviation, "deviation"), as_span(edf, "edf"),
                                        input_unit)
                          .to_json(input_unit));
      },
      "tau_s"_a, "deviation"_a, "edf"_a, "input_unit"_a = "deg/h",
      "Slope read-off on an Allan deviation (IEEE Std 952-1997 C.1): N at tau = 1 s on the -1/2 line, B =\n"
      "sigma / 0.664 on the flat part, K at tau = 3 s on the +1/2 line. Returns a Record.");
}

}  // namespace inertest::python

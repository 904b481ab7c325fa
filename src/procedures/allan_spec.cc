// Allan variance and the noise terms of a rate record, GJB 2426A-2004 5.12.5.4.2 (eqs. (30)-(31)),
// IEEE Std 952-1997 Annex C, NIST SP 1065: the analysis of allan/allan.h on one channel of a record,
// or on several channels read in one pass (an IMU's axes, allan/allan_channels.h). Declared once
// (issue 22): the command `inertest allan`, the plan kind "allan" and the Python function
// `inertest.allan` come from this file, with one name per parameter (the plan key and the Python
// keyword; the flag its kebab-case, `--rate` and `--psd-segment` kept as the README writes them).
// The result writes its own JSON object and text (AllanResult, AllanChannels): a tau table, and one
// object per channel with --columns.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/allan/allan.h"
#include "inertest/allan/allan_channels.h"
#include "inertest/allan/filter_parameters.h"
#include "inertest/allan/noise_terms.h"
#include "inertest/allan/tau_grid.h"
#include "inertest/core/json_text.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/core/units.h"
#include "inertest/io/atomic_write.h"
#include "inertest/io/rate_record.h"
#include "inertest/io/time_stamps.h"
#include "inertest/procedures/instrument_sensor.h"

namespace inertest {
namespace {

struct AllanParameters {
  std::string format = "auto";
  std::optional<std::string> column;
  std::optional<std::vector<std::string>> columns;  // several channels in one pass
  std::optional<double> sample_rate_hz;
  std::optional<std::string> input_unit;
  std::string taus = "octave";
  std::optional<double> scale_factor;
  std::optional<std::string> output_unit;  // of the raw output scale_factor divides
  std::string estimators = "all";
  std::optional<FitRange> fit_range;
  bool psd = false;
  std::optional<std::string> psd_window;
  std::size_t psd_segment_length = 0;  // 0: automatic
  std::size_t threads = 2;
  std::vector<std::string> export_to;  // FORMAT FILE

  RateRecordSource source(const std::string& path) const {
    RateRecordSource source;
    source.path = path;
    source.set_format(format);
    if (column) source.column = ColumnSelector::parse(*column);
    return source;
  }

  // The options of the analysis; the sample rate is the one given (check() holds it against a text
  // record's time column) or, failing that, the one the record stores (HDF5 sample_rate_hz, TDMS
  // wf_increment, a text record's time column named with its unit, as bias reads it), else an Error
  // naming the file and what a time column shows.
  // `pulse_counts`: the output counts pulses per sample interval (ProcedureCall::pulse_counts).
  AllanOptions options(const RateRecordSource& source, bool pulse_counts) const {
    AllanOptions options;
    const RateRecordFormat stored_as = resolve_rate_record_format(source);
    const bool text = stored_as == RateRecordFormat::kCsv;
    if (sample_rate_hz) {
      options.sample_rate_hz = *sample_rate_hz;
    } else if (columns && channel_record_format_of(stored_as)) {
      // several channels of a record that stores each one's rate: each its own (allan_channels.cc)
    } else if (const std::optional<double> stored = stored_sample_rate(source)) {
      options.sample_rate_hz = *stored;
    } else if (const std::optional<RecordTimeColumn> time = text ? find_record_time_column(source.path) : std::nullopt;
               time && time->unit_stated) {
      options.sample_rate_hz = time->sample_rate_hz();  // a time column named with its unit (time_s)
    } else {
      throw Error(SourceLocation{source.path, 0, 0},
                  "the record stores no sample rate: give sample_rate_hz (--rate)" +
                      (time ? fmt::format("; its time column '{}' steps {:.6g} s ({:.6g} Hz){}", time->name,
                                          time->sample_interval_s, 1.0 / time->sample_interval_s,
                                          time->unit_stated ? "" : " if in s")
                            : ""));
    }
    options.taus = taus;
    options.estimators = EstimatorSet::parse(estimators);
    options.worker_count = threads;
    options.fit_range = fit_range;
    if (scale_factor) {
      // raw / (output per deg/s) = deg/s; times 3600 = deg/h. A record that stores a rate or an
      // acceleration (HDF5 units, TDMS unit_string) is no raw output: dividing its deg/s by K again
      // gave a mean of 449 deg/h for 0.25 deg/s.
      if (!columns) {
        if (const std::optional<std::string> stored = resolved_unit(source, std::nullopt);
            stored && sensor_kind_of(*stored) != SensorKind::kOther) {
          throw ParameterError("scale_factor", "the record stores its samples in " + *stored +
                                                   ", not a raw output: scale_factor divides a raw output by K "
                                                   "(leave it out, or give input_unit)");
        }
      }
      options.scale = 3600.0 / *scale_factor;
      if (pulse_counts) {
        // Pulses counted per sample interval are pulse/s times the interval: K is output per deg/s.
        if (options.sample_rate_hz == 0.0) {
          throw ParameterError("output_unit", "pulses per sample interval need the one sample rate of the channels: "
                                              "give sample_rate_hz (--rate)");
        }
        options.scale *= options.sample_rate_hz;
      }
      options.input_unit = "deg/h";
    } else if (!columns) {
      // The unit given, else the one the record stores (HDF5 units, TDMS unit_string), else deg/h.
      if (const std::optional<std::string> unit = resolved_unit(source, input_unit)) options.input_unit = *unit;
    }
    if (psd || psd_window || psd_segment_length > 0) {
      WelchOptions welch;
      welch.window = parse_spectral_window(psd_window.value_or("hann"));
      welch.segment_length = psd_segment_length;
      options.psd = welch;
    }
    return options;
  }
};

// The result: one channel (AllanResult's JSON and text) or several ({"channels": {...}}).
struct AllanRun {
  AllanChannels channels;
  bool several = false;
};

void check(const ProcedureCall& call, const AllanParameters& parameters) {
  if (parameters.column && parameters.columns) throw ParameterError("columns", "column and columns exclude each other");
  if (parameters.scale_factor) {
    if (parameters.input_unit) {
      throw ParameterError("input_unit", "input_unit and scale_factor exclude each other: scaled output is in deg/h");
    }
    if (!(*parameters.scale_factor != 0.0) || !std::isfinite(*parameters.scale_factor)) {
      throw ParameterError("scale_factor", "scale_factor must be finite and nonzero");
    }
  } else if (parameters.output_unit) {
    throw ParameterError("output_unit", "output_unit is the unit of the raw output that scale_factor divides: give "
                                        "scale_factor, or the samples' unit as input_unit");
  }
  check_parameter("export", [&] {
    if (parameters.export_to.empty()) return;
    if (parameters.export_to.size() != 2) throw Error("export takes FORMAT and FILE");
    parse_filter_format(parameters.export_to[0]);
  });
  if (parameters.output_unit) check_parameter("output_unit", [&] { Unit::parse(*parameters.output_unit); });
  check_parameter("estimators", [&] { EstimatorSet::parse(parameters.estimators); });
  check_parameter("taus", [&] { TauGrid::parse(parameters.taus); });
  check_parameter("fit_range", [&] {
    NoiseFitOptions fit;
    fit.fit_range = parameters.fit_range;
    fit.validate();
  });
  check_parameter("format", [&] { RateRecordSource().set_format(parameters.format); });
  RateRecordSource source;
  check_parameter("column", [&] {
    source = parameters.source(call.files.at("record"));
    if (parameters.column && source.format == RateRecordFormat::kBinary) {
      throw Error("a raw binary record holds one channel: column does not apply");
    }
  });
  check_parameter("columns", [&] {
    if (!parameters.columns) return;
    if (parameters.columns->empty()) throw Error("name at least one channel");
    for (auto column = parameters.columns->begin(); column != parameters.columns->end(); ++column) {
      if (column->empty()) throw Error("an empty channel name in columns");
      ColumnSelector::parse(*column);
      if (std::find(parameters.columns->begin(), column, *column) != column) {
        throw Error("channel '" + *column + "' is asked for twice");
      }
    }
  });
  check_parameter("input_unit", [&] {
    if (!parameters.input_unit || parameters.columns) return;  // per channel: checked once the names are read
    if (parameters.input_unit->find_first_of(",=") != std::string::npos) {
      throw Error("units per channel (" + *parameters.input_unit + ") need columns, not column");
    }
    Unit::parse(*parameters.input_unit);
  });
  AllanOptions options = parameters.options(source, call.pulse_counts);
  if (options.sample_rate_hz == 0.0) options.sample_rate_hz = 1.0;  // each channel's own, read with the channels
  options.validate();
  if (resolve_rate_record_format(source) == RateRecordFormat::kCsv) {
    check_sample_rate_against_time_column(source.path, options.sample_rate_hz);  // and its gaps
  }
}

// A word of a command line, quoted for a POSIX shell when it needs to be.
std::string shell_word(const std::string& word) {
  const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](unsigned char c) {
    return std::isalnum(c) != 0 || std::string_view("_-./:=,+^@%").find(static_cast<char>(c)) != std::string_view::npos;
  });
  if (plain) return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// The command line of this run, for an export's header: `inertest allan FILE` and each parameter
// whose value is not its default, as the command line takes it, whether the run came from the
// command line, a plan or Python, so that the file says how to get its numbers again.
std::string command_line(const ProcedureCall& call) {
  const ProcedureSpec& spec = *find_procedure_spec("allan");
  std::vector<std::string> words = {"inertest", "allan", call.files.at("record")};
  for (const ParameterSpec& parameter : spec.parameters) {
    const auto given = call.parameters.find(parameter.name);
    const auto fallback = spec.defaults.find(parameter.name);
    if (given == call.parameters.end() || given->is_null() ||
        (fallback != spec.defaults.end() && fallback->second == *given)) {
      continue;
    }
    words.push_back(parameter.command_line_option());
    const auto text_of = [](const nlohmann::json& value) { return value.is_string() ? value.get<std::string>() : json_text(value); };
    if (parameter.type == ParameterType::boolean) continue;  // the flag alone
    if (parameter.name == "output_unit" && call.pulse_counts) {
      words.push_back("pulse");  // the counts the record holds (pulse/s is the unit they were read as)
    } else if (!given->is_array()) {
      words.push_back(text_of(*given));
    } else if (parameter.cli_values > 0) {
      for (const nlohmann::json& value : *given) words.push_back(text_of(value));
    } else {
      std::string list;
      const char separator = parameter.type == ParameterType::numbers ? parameter.cli_separator : ',';
      for (const nlohmann::json& value : *given) list += (list.empty() ? "" : std::string(1, separator)) + text_of(value);
      words.push_back(list);
    }
  }
  std::string line;
  for (const std::string& word : words) line += (line.empty() ? "" : " ") + shell_word(word);
  return line;
}

AllanRun run(const ProcedureCall& call, const AllanParameters& parameters) {
  const std::string& file = call.files.at("record");
  const RateRecordSource source = parameters.source(file);
  const AllanOptions options = parameters.options(source, call.pulse_counts);
  AllanRun result;
  if (!parameters.columns) {
    result.channels.channels.push_back(
        {parameters.column.value_or("rate"), allan_variance_of_file(source, options, call.progress)});
  } else {
    std::vector<ColumnSelector> selectors;
    for (const std::string& column : *parameters.columns) selectors.push_back(ColumnSelector::parse(column));
    result.channels = allan_variance_of_channels_in_file(source, selectors, parameters.input_unit.value_or(""), options,
                                                         parameters.scale_factor.has_value(), call.progress);
    result.several = true;
  }
  if (!parameters.export_to.empty()) {
    write_file_atomically(call.output_path(parameters.export_to[1]),
                          format_filter_parameters(filter_noise_parameters(result.channels),
                                                   parse_filter_format(parameters.export_to[0]), command_line(call)));
  }
  return result;
}

// In a plan, the [instrument] says what a record of one channel holds, where the record does not
// (HDF5 units, TDMS unit_string win): an output in a unit of angular rate or acceleration is the
// samples' unit; a gyro's output in another (pulse/s, V) is divided by its nominal scale factor.
// The step's input_unit or scale_factor (they exclude each other) takes precedence; the columns of
// an IMU record hold rates and accelerations, each named by input_unit. Without either from the
// instrument the samples are in deg/h, the command line's default. (A step that took neither read a
// MEMS gyro's deg/s, or a FOG's pulse/s, as deg/h.)
std::optional<std::string> stored_unit(const ProcedureCall& call) {
  try {
    RateRecordSource source;
    source.path = call.files.at("record");
    source.set_format(call.parameters.value("format", std::string("auto")));
    if (call.parameters.contains("column")) source.column = ColumnSelector::parse(call.parameters.at("column").get<std::string>());
    return resolved_unit(source, std::nullopt);
  } catch (const Error&) {
    return std::nullopt;  // a bad format, column or record: the step's check says it, at its key
  }
}

bool takes_instrument_output_unit(const ProcedureCall& call, const nlohmann::json& instrument) {
  if (call.parameters.contains("scale_factor") || call.parameters.contains("columns")) return false;
  return sensor_kind_of(instrument.at("output_unit").get<std::string>()) != SensorKind::kOther && !stored_unit(call);
}

bool takes_instrument_scale_factor(const ProcedureCall& call, const nlohmann::json& instrument) {
  if (call.parameters.contains("input_unit") || call.parameters.contains("columns")) return false;
  if (!instrument_is_gyro(call, instrument)) return false;
  const std::optional<std::string> stored = stored_unit(call);
  return !stored || sensor_kind_of(*stored) == SensorKind::kOther;  // a stored raw unit (pulse/s) takes K
}

// The step has a scale factor, given or its instrument's (declared before output_unit).
bool divides_by_scale_factor(const ProcedureCall& call, const nlohmann::json&) {
  return call.parameters.contains("scale_factor");
}

}  // namespace

ProcedureSpec allan_spec();

ProcedureSpec allan_spec() {
  const FieldRole hidden = FieldRole::hidden;
  return ProcedureDefinition<AllanParameters, AllanRun>(
             "allan", "Allan variance and random walk coefficient", kAllanClause,
             "ADEV, OADEV, MDEV, HDEV, OHDEV, TOTDEV with chi-squared bounds (IEEE Std 952-1997 Annex C,\n"
             "NIST SP 1065), and the noise terms Q, N (ARW), B (bias instability), K (RRW), R (rate ramp) by the\n"
             "fit of GJB eq. (30) and by slope read-off. FILE: one channel of rate samples, text (csv), raw\n"
             "binary (f64, f32, i32 or i16, le or be), or a channel of a MATLAB .mat, HDF5 or NI TDMS file (found by its magic\n"
             "bytes; --column names the channel); --columns several channels in one pass. Text is parsed once,\n"
             "into memory; the others stream once.")
      .json_procedure_is("allan_variance")
      .chinese_title("Allan 方差与随机游走系数")
      .report_method(
          "Overlapping Allan variance of the rate record (IEEE Std 952-1997 Annex C) with confidence intervals; the "
          "noise model σ²(τ) = Σ A_m·τ^m (m = −2…2) is fitted and each term read at its characteristic slope.",
          "对角速率记录计算重叠 Allan 方差（IEEE Std 952-1997 附录 C）及其置信区间；拟合噪声模型 σ²(τ) = Σ A_m τ^m（m = "
          "-2..2），各噪声项按其特征斜率读取。")
      .input(InputSpec("record", "rate record").read_from_file("FILE", "file").holds_raw_samples())
      .parameter(ParameterSpec("format", "how FILE is stored: auto (.mat, HDF5 or TDMS by magic bytes, else text), csv, "
                                         "mat, hdf5, tdms, or raw binary: f64, f32, i32 or i16, optionally with le/be "
                                         "(e.g. i32be; little-endian without)"),
                 &AllanParameters::format)
      .parameter(ParameterSpec("column", "text column (header name or 1-based index), or channel: group/channel, "
                                         "struct.field (default: the only one)"),
                 &AllanParameters::column)
      .parameter(ParameterSpec("columns", "several channels in one pass, e.g. gx,gy,gz,ax,ay,az (names or indices): "
                                          "JSON {\"channels\": {...}}"),
                 &AllanParameters::columns)
      .parameter(ParameterSpec("sample_rate_hz", "sample rate (default: the rate the file stores; one that "
                                                 "contradicts it is an error)")
                     .unit_is("Hz")
                     .command_line_name_is("rate")
                     .instrument_gives("sample_rate_hz"),
                 &AllanParameters::sample_rate_hz)
      .parameter(ParameterSpec("input_unit", "unit of the samples (default: the one the record stores, HDF5 units or "
                                             "TDMS unit_string, else deg/h; in a plan, [instrument] output_unit when it is "
                                             "a rate or an acceleration); with columns per channel too: "
                                             "deg/s,ax=m/s^2 (an acceleration unit gives the accelerometer's noise terms)")
                     .instrument_gives("output_unit")
                     .instrument_gives_if(takes_instrument_output_unit),
                 &AllanParameters::input_unit)
      .parameter(ParameterSpec("taus", "octave, decade, all, N/decade or a comma list of tau in s; the noise terms are "
                                       "fitted on those an octave or more apart"),
                 &AllanParameters::taus)
      .parameter(ParameterSpec("scale_factor", "K, output units per deg/s: the raw output is divided by K and "
                                               "reported in deg/h (excludes input_unit; in a plan, a gyro's [instrument] "
                                               "nominal_scale_factor when the step gives no input_unit)")
                     .instrument_gives("nominal_scale_factor")
                     .instrument_gives_if(takes_instrument_scale_factor),
                 &AllanParameters::scale_factor)
      .parameter(ParameterSpec("output_unit", "unit of the raw output that scale_factor divides (pulse: counts per "
                                              "sample interval, read as pulse/s; in a plan, [instrument] output_unit "
                                              "with its nominal_scale_factor)")
                     .instrument_gives("output_unit")
                     .instrument_gives_if(divides_by_scale_factor),
                 &AllanParameters::output_unit)
      .parameter(ParameterSpec("estimators", "all, or a comma list of adev, oadev, mdev, hdev, ohdev, totdev"),
                 &AllanParameters::estimators)
      .parameter(ParameterSpec("fit_range", "TMIN:TMAX, the taus of the eq. (30) fit (default: chosen automatically, "
                                            "see noise.fit.fit_range); [tau_min, tau_max] in a plan")
                     .unit_is("s")
                     .numbers(':'),
                 [](AllanParameters& parameters, const nlohmann::json& value) {
                   const auto range = value.get<std::vector<double>>();
                   if (range.size() != 2) {
                     throw ParameterError("fit_range", "the fit range must read TMIN:TMAX in s ([tau_min, tau_max] in a plan)");
                   }
                   parameters.fit_range = FitRange{range[0], range[1]};
                 })
      .parameter(ParameterSpec("psd", "also the power spectral density (Welch, IEEE Std 952-1997 Annex C): its noise "
                                      "terms beside the Allan fit, periodic components (reads a streamed record into "
                                      "memory)"),
                 &AllanParameters::psd)
      .parameter(ParameterSpec("psd_window", "the Welch window, default hann (implies psd)")
                     .one_of({"hann", "hamming", "blackman-harris", "rectangular"}),
                 &AllanParameters::psd_window)
      .parameter(ParameterSpec("psd_segment_length", "samples per Welch segment, 0: a power of two giving 16-32 "
                                                     "segments (a length implies psd)")
                     .command_line_name_is("psd-segment"),
                 &AllanParameters::psd_segment_length)
      .parameter(ParameterSpec("threads", "worker threads"), &AllanParameters::threads)
      .parameter(ParameterSpec("export", "FORMAT FILE: the noise parameters a navigation filter takes, FORMAT kalibr "
                                         "(imu.yaml), matlab (gyroparams/accelparams), gnss-ins-sim (IMU error "
                                         "dictionary) or json; in a plan a relative FILE is beside results.json")
                     .values_on_command_line(2)
                     .writes_file(),
                 &AllanParameters::export_to)
      .checked_by(check)
      .written_by(
          [](const AllanRun& result) {
            return result.several ? result.channels.to_json() : result.channels.channels.front().result.to_json();
          },
          [](const AllanRun& result) {
            return result.several ? result.channels.report() : result.channels.channels.front().result.report();
          })
      // Listed in the report in this order: the noise terms first.
      .declare({"noise", FieldRole::headline, "noise terms", "噪声项",
                "GJB 2426A-2004 eqs. (30)-(31); IEEE Std 952-1997 C.1"})
      .declare({"record_length", FieldRole::detail, "record length", "记录时长", ""})
      .declare({"mean", FieldRole::detail, "mean", "均值", ""})
      .declare({"psd", FieldRole::detail, "power spectral density", "功率谱密度", "IEEE Std 952-1997 Annex C"})
      .declare({"channels", FieldRole::headline, "channels", "通道", "issue 19: one object per channel"})
      .declare({"standard", hidden, "standards", "标准", ""})
      .declare({"sample_count", hidden, "samples", "样本数", ""})
      .declare({"sample_rate_hz", hidden, "sample rate", "采样频率", ""})
      .declare({"input_unit", hidden, "input unit", "输入单位", ""})
      .declare({"tau_grid", hidden, "tau grid", "τ 网格", ""})
      .declare({"confidence_level", hidden, "confidence level", "置信水平", ""})
      .declare({"tau", hidden, "averaging times", "平均时间", ""})
      .declare({"averaging_factor", hidden, "averaging factors", "平均因子", ""})
      .declare({"noise_type", hidden, "dominant noise per tau", "主导噪声", "NIST SP 1065 5.6"})
      .declare({"alpha", hidden, "noise exponent alpha per tau", "噪声指数 α", "NIST SP 1065 5.6"})
      // The deviation curves, with bounds; the report draws one of them (allan_plots.cc).
      .declare({"adev", hidden, "ADEV", "ADEV", "IEEE Std 952-1997 Annex C"})
      .declare({"oadev", hidden, "OADEV", "OADEV", "NIST SP 1065 eq. (11)"})
      .declare({"mdev", hidden, "MDEV", "MDEV", "NIST SP 1065"})
      .declare({"hdev", hidden, "HDEV", "HDEV", "NIST SP 1065"})
      .declare({"ohdev", hidden, "OHDEV", "OHDEV", "NIST SP 1065"})
      .declare({"totdev", hidden, "TOTDEV", "TOTDEV", "NIST SP 1065 eq. (25)"})
      .declare({"warnings", hidden, "warnings", "警告", ""})
      .unit_of("record_length", "s")
      .compute(run);
}

}  // namespace inertest

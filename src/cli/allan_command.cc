// inertest allan FILE [--rate HZ] [--format auto|csv|f64|f32|mat|hdf5|tdms] [--column N | --columns A,B,..]
//                [--taus SPEC] [--input-unit U | A=U,B=U2] [--scale-factor K] [--estimators LIST]
//                [--fit-range TMIN:TMAX] [--psd] [--psd-window W] [--psd-segment N]
//                [--export kalibr|matlab|gnss-ins-sim|json FILE] [--threads N] [--json]
#include <cmath>
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/allan/allan.h"
#include "inertest/allan/allan_channels.h"
#include "inertest/allan/filter_parameters.h"
#include "inertest/io/atomic_write.h"

namespace inertest::cli {
namespace {

std::string join(const std::vector<std::string>& items) {
  std::string text;
  for (const auto& item : items) text += (text.empty() ? "" : ",") + item;
  return text;
}

struct Arguments {
  RateRecordSource source;
  std::string format = "auto";
  std::string column;
  std::vector<std::string> columns;
  std::string input_units;
  std::vector<std::string> export_target;  // FORMAT FILE
  bool psd = false;
  std::string psd_window = "hann";
  std::size_t psd_segment = 0;
  std::optional<double> sample_rate_hz;
  std::string estimators = "all";
  std::string fit_range;
  double scale_factor = 0.0;
  bool scaled = false;
  AllanOptions options;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "allan",
      "Allan variance of a rate record (GJB 2426A-2004 5.12.5.4.2, IEEE Std 952-1997 Annex C, NIST SP 1065):\n"
      "ADEV, OADEV, MDEV, HDEV, OHDEV, TOTDEV with chi-squared bounds, and the noise terms Q, N (ARW),\n"
      "B (bias instability), K (RRW), R (rate ramp) by the fit of GJB eq. (30) and by slope read-off.\n"
      "FILE: one channel of rate samples, text (csv), raw little-endian f64/f32, or a channel of a MATLAB .mat,\n"
      "HDF5 or NI TDMS file (found by its magic bytes; --column names the channel). Text is parsed once, into\n"
      "memory; the others stream once.");
  command->add_option("FILE", arguments->source.path, "rate record")->required()->check(CLI::ExistingFile);
  command->add_option("--rate", arguments->sample_rate_hz,
                      "sample rate in Hz (default: the rate the file stores; one that contradicts it is an error)");
  command->add_option("--format", arguments->format, "auto, csv, f64 or f32 (raw little-endian), mat, hdf5 or tdms")
      ->capture_default_str();
  CLI::Option* column = command->add_option(
      "--column", arguments->column, "text column (header name or 1-based index), or channel: group/channel, struct.field");
  command
      ->add_option("--columns", arguments->columns,
                   "several channels in one pass, e.g. gx,gy,gz,ax,ay,az (names or indices): JSON {\"channels\": {...}}")
      ->delimiter(',')
      ->excludes(column);
  command->add_option("--taus", arguments->options.taus, "octave, decade, all, N/decade or a list of tau in s; the noise terms are fitted on those an octave or more apart")
      ->capture_default_str();
  CLI::Option* unit = command->add_option(
      "--input-unit", arguments->input_units,
      "unit of the samples (default deg/h); with --columns per channel too: gx=deg/s,ax=m/s^2 (an acceleration unit "
      "gives the accelerometer's noise terms)");
  command
      ->add_option_function<double>(
          "--scale-factor",
          [arguments](double k) {
            arguments->scale_factor = k;
            arguments->scaled = true;
          },
          "K, output units per deg/s: the raw output is divided by K and reported in deg/h")
      ->excludes(unit);
  command->add_option("--estimators", arguments->estimators, "comma list of adev,oadev,mdev,hdev,ohdev,totdev")
      ->capture_default_str();
  command->add_option("--fit-range", arguments->fit_range,
                      "TMIN:TMAX in s: the taus of the eq. (30) fit (default: chosen automatically, see the JSON's "
                      "noise.fit.fit_range)");
  command
      ->add_option("--export", arguments->export_target,
                   "FORMAT FILE: the noise parameters a navigation filter takes, FORMAT kalibr (imu.yaml), matlab "
                   "(gyroparams/accelparams), gnss-ins-sim (IMU error dictionary) or json")
      ->expected(2);
  command->add_flag("--psd", arguments->psd,
                    "also the power spectral density (Welch, IEEE Std 952-1997 Annex C): its noise terms beside the "
                    "Allan fit, periodic components (reads a streamed record into memory)");
  command->add_option("--psd-window", arguments->psd_window, "hann, hamming, blackman-harris or rectangular (implies --psd)")
      ->capture_default_str();
  command->add_option("--psd-segment", arguments->psd_segment,
                      "samples per Welch segment (default: a power of two giving 16-32 segments; implies --psd)");
  command->add_option("--threads", arguments->options.worker_count, "worker threads")->capture_default_str();
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments, command] {
    arguments->source.format = parse_rate_record_format(arguments->format);
    if (!arguments->column.empty()) arguments->source.column = ColumnSelector::parse(arguments->column);
    if (arguments->sample_rate_hz) {
      arguments->options.sample_rate_hz = *arguments->sample_rate_hz;
    } else if (const std::optional<double> stored = stored_sample_rate(arguments->source)) {
      arguments->options.sample_rate_hz = *stored;
    } else {
      throw Error(SourceLocation{arguments->source.path, 0, 0}, "the record stores no sample rate: give --rate");
    }
    arguments->options.estimators = EstimatorSet::parse(arguments->estimators);
    if (!arguments->fit_range.empty()) arguments->options.fit_range = parse_fit_range(arguments->fit_range);
    if (arguments->scaled) {
      const double k = arguments->scale_factor;
      if (!(k != 0.0) || !std::isfinite(k)) throw Error("--scale-factor must be finite and nonzero");
      // raw / (output per deg/s) = deg/s; times 3600 = deg/h (as the plan key scale_factor).
      arguments->options.scale = 3600.0 / k;
      arguments->options.input_unit = "deg/h";
    }
    if (arguments->psd || command->count("--psd-window") > 0 || command->count("--psd-segment") > 0) {
      WelchOptions welch;
      welch.window = parse_spectral_window(arguments->psd_window);
      welch.segment_length = arguments->psd_segment;
      arguments->options.psd = welch;
    }
    std::optional<FilterFormat> export_format;
    if (!arguments->export_target.empty()) export_format = parse_filter_format(arguments->export_target[0]);
    AllanChannels channels;
    if (arguments->columns.empty()) {
      if (!arguments->input_units.empty()) arguments->options.input_unit = arguments->input_units;
      const std::string name = arguments->column.empty() ? "rate" : arguments->column;
      channels.channels.push_back(
          {name, allan_variance_of_file(arguments->source, arguments->options, terminal_progress())});
    } else {
      std::vector<ColumnSelector> selectors;
      for (const std::string& c : arguments->columns) selectors.push_back(ColumnSelector::parse(c));
      channels = allan_variance_of_channels_in_file(arguments->source, selectors, arguments->input_units,
                                                    arguments->options, terminal_progress());
    }
    // The export is written before anything is printed: a failure leaves no partial output.
    if (export_format) {
      const std::string command_line = "inertest allan " + arguments->source.path +
                                       (arguments->columns.empty() ? "" : " --columns " + join(arguments->columns));
      write_file_atomically(arguments->export_target[1],
                            format_filter_parameters(filter_noise_parameters(channels), *export_format, command_line));
    }
    if (arguments->columns.empty()) {
      const AllanResult& result = channels.channels.front().result;
      print_result(result.to_json(), result.report(), arguments->json);
    } else {
      print_result(channels.to_json(), channels.report(), arguments->json);
    }
    return 0;
  };
}

const bool registered = register_command("allan", setup);

}  // namespace
}  // namespace inertest::cli

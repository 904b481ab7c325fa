// inertest inspect FILE: what a record holds (rows, columns, and per column count, mean, standard
// deviation, min, max), read exactly as the procedures read it. A first look at lab data: it warns
// about a constant (stuck) channel and, with --time-column, checks the time stamps for steps
// backwards and gaps (io/time_stamps.h). A MATLAB .mat, HDF5 or TDMS record (found by its magic
// bytes) lists its channels with their stored types, lengths, units and sample rates.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "command.h"
#include "inertest/io/binary_record.h"
#include "inertest/io/channel_record.h"
#include "inertest/io/text_table.h"
#include "inertest/io/time_stamps.h"
#include "inertest/numerics/statistics.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string file;
  std::string format = "auto";
  std::size_t channels = 1;
  std::string time_column;
  std::string gaps = "stop";
  std::optional<double> sample_interval;
  bool json = false;
};

nlohmann::json describe(const std::string& name, const std::vector<double>& values, nlohmann::json& warnings) {
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  nlohmann::json column = {{"name", name}, {"count", values.size()}, {"mean", mean(values)},
                           {"min", *low},  {"max", *high}};
  if (values.size() > 1) column["standard_deviation"] = sample_standard_deviation(values);
  // A channel that never changes is a stuck sensor or a wrong column; procedures that need its
  // variation (a slope, an Allan variance) will refuse it, so say so on the first look.
  if (is_constant(values)) {
    warnings.push_back(fmt::format("column '{}' is constant: all {} samples equal {:.10g} (a stuck channel?)", name,
                                   values.size(), *low));
  }
  return column;
}

// A channel of a .mat, HDF5 or TDMS record: what the file stores about it, and for a numeric channel
// the statistics of describe(), accumulated as the channel streams (Welford's running variance).
nlohmann::json describe_channel(ChannelRecord& record, std::size_t index, nlohmann::json& warnings) {
  const ChannelInfo& info = record.channels()[index];
  nlohmann::json channel = {{"name", info.name}, {"type", info.type}, {"count", info.length}};
  if (!info.unit.empty()) channel["unit"] = info.unit;
  if (info.sample_rate_hz) channel["sample_rate_hz"] = *info.sample_rate_hz;
  if (info.start_time_s) channel["start_time_s"] = *info.start_time_s;
  for (const std::string* problem : {&info.sample_rate_problem, &info.unit_problem}) {
    if (!problem->empty()) warnings.push_back(fmt::format("channel '{}': {}", info.name, *problem));
  }
  if (!info.numeric || info.length == 0) return channel;
  double running_mean = 0.0;
  double squares = 0.0;
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  std::size_t count = 0;
  stream_channel(record, index, [&](std::span<const double> samples) {
    for (const double value : samples) {
      ++count;
      const double delta = value - running_mean;
      running_mean += delta / static_cast<double>(count);
      squares += delta * (value - running_mean);
      low = std::min(low, value);
      high = std::max(high, value);
    }
  });
  channel["mean"] = running_mean;
  channel["min"] = low;
  channel["max"] = high;
  if (count > 1) channel["standard_deviation"] = std::sqrt(squares / static_cast<double>(count - 1));
  if (count > 1 && low == high) {  // as is_constant: one sample is not a stuck channel
    warnings.push_back(fmt::format("channel '{}' is constant: all {} samples equal {:.10g} (a stuck channel?)", info.name,
                                   count, low));
  }
  return channel;
}

// The channel format named by --format, or found by the magic bytes under "auto".
std::optional<ChannelRecordFormat> channel_format_of(const std::string& format, const std::string& file) {
  if (format == "mat") return ChannelRecordFormat::kMat;
  if (format == "hdf5") return ChannelRecordFormat::kHdf5;
  if (format == "tdms") return ChannelRecordFormat::kTdms;
  if (format == "auto") return detect_channel_record_format(file);
  return std::nullopt;
}

// The 0-based index of the time column among all columns of the table.
std::size_t find_time_column(const TextTable& table, const std::string& text) {
  const ColumnSelector selector = ColumnSelector::parse(text);
  if (selector.index > 0) {
    if (selector.index > table.columns.size()) {
      throw Error(SourceLocation{table.source, table.first_data_line, 0},
                  fmt::format("time column {} asked for, but the record has {} columns", selector.index,
                              table.columns.size()));
    }
    return selector.index - 1;
  }
  const auto it = std::find(table.names.begin(), table.names.end(), selector.name);
  if (table.header_line == 0) {
    throw Error(SourceLocation{table.source, table.first_data_line, 1},
                "time column '" + selector.name + "' asked for by name, but the record has no header row");
  }
  if (it == table.names.end()) {
    std::string known;
    for (const auto& name : table.names) known += (known.empty() ? "" : ", ") + name;
    throw Error(SourceLocation{table.source, table.header_line, 1},
                "no time column '" + selector.name + "' in the header (columns: " + known + ")");
  }
  return static_cast<std::size_t>(it - table.names.begin());
}

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "inspect",
      "Read a record as the procedures do and describe it: rows, columns, and per column the count,\n"
      "mean, standard deviation (n-1), min and max, in the record's own units. Text records: CSV, TSV,\n"
      "semicolon or whitespace separated, header optional, '#' comments. Binary: --format f64|f32|i32|i16\n"
      "(suffix be for big endian) with --channels interleaved channels. A constant column gives a warning.\n"
      "MATLAB .mat, HDF5 and NI TDMS records (found by their magic bytes, or --format mat|hdf5|tdms): every\n"
      "channel with its stored type, length, unit and sample rate, and the statistics of the numeric ones.\n"
      "--time-column checks the time stamps: going backwards is an error; a step of more than 1.5 sample\n"
      "intervals is a gap (of stamps rounded coarser than the interval, 800 Hz in ms, a step longer than the\n"
      "interval by more than their quantum), and --gaps says what to do: stop (an error), split (report the\n"
      "contiguous segments) or interpolate (fill the missing samples linearly and count them).");
  command->add_option("FILE", arguments->file, "record to read")->required();
  command->add_option("--format", arguments->format,
                      "auto (.mat, HDF5, TDMS by magic bytes, else text), csv (any text table), mat, hdf5, tdms, or a "
                      "binary sample type")
      ->capture_default_str();
  command->add_option("--channels", arguments->channels, "interleaved channels of a binary record")
      ->capture_default_str();
  command->add_option("--time-column", arguments->time_column, "time column of a text record (name or 1-based number)");
  command->add_option("--gaps", arguments->gaps, "at a gap in the time stamps: stop, split or interpolate")
      ->check(CLI::IsMember({"stop", "split", "interpolate"}))
      ->capture_default_str();
  command->add_option("--sample-interval", arguments->sample_interval,
                      "nominal sample interval in the time column's unit (default: the median step, or the mean step "
                      "between gaps where the stamps are coarse, e.g. epoch seconds or 800 Hz in ms)");
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    nlohmann::json columns = nlohmann::json::array();
    nlohmann::json warnings = nlohmann::json::array();
    nlohmann::json time_report;
    std::size_t rows = 0;
    const std::optional<ChannelRecordFormat> channel_format = channel_format_of(arguments->format, arguments->file);
    if (channel_format) {
      if (!arguments->time_column.empty()) throw Error("--time-column needs a text record: a .mat, HDF5 or TDMS record stores its sample rate");
      const std::unique_ptr<ChannelRecord> record = open_channel_record(arguments->file, *channel_format);
      for (std::size_t i = 0; i < record->channels().size(); ++i) {
        rows = std::max(rows, static_cast<std::size_t>(record->channels()[i].length));
        columns.push_back(describe_channel(*record, i, warnings));
      }
    } else if (arguments->format == "csv" || arguments->format == "auto") {
      TextTableOptions options;
      options.record_row_lines = !arguments->time_column.empty();
      TextTable table = read_text_table(arguments->file, options);
      if (!arguments->time_column.empty()) {
        TimeStampOptions time_options;
        time_options.policy = parse_gap_policy(arguments->gaps);
        time_options.sample_interval = arguments->sample_interval;
        const std::size_t time_column = find_time_column(table, arguments->time_column);
        time_report = with_file_context(arguments->file, [&] { return check_time_stamps(table, time_column, time_options); }).to_json();
      }
      rows = table.rows();
      for (std::size_t i = 0; i < table.columns.size(); ++i) {
        const std::string name = table.names[i].empty() ? std::to_string(i + 1) : table.names[i];
        columns.push_back(describe(name, table.columns[i], warnings));
      }
    } else {
      if (!arguments->time_column.empty()) throw Error("--time-column needs a text record (--format csv)");
      BinaryFormat format = BinaryFormat::parse(arguments->format);
      format.channels = arguments->channels;
      if (format.channels == 0) throw Error("--channels is 0: a binary record holds at least one channel");
      for (std::size_t c = 0; c < format.channels; ++c) {
        format.channel = c;
        const auto values = read_binary_record(arguments->file, format);
        rows = values.size();
        columns.push_back(describe(std::to_string(c + 1), values, warnings));
      }
    }
    nlohmann::json json = {{"file", arguments->file}, {"rows", rows}, {"columns", columns}, {"warnings", warnings}};
    std::string report = fmt::format("{}: {} rows, {} columns\n", arguments->file, rows, columns.size());
    if (channel_format) {
      json["format"] = channel_record_format_name(*channel_format);
      report = fmt::format("{}: {} record, {} channels\n", arguments->file, channel_record_format_name(*channel_format),
                           columns.size());
    }
    for (const auto& c : columns) {
      if (channel_format) {
        report += fmt::format("  {:<24} {:<10} {:>12} samples", c["name"].get<std::string>(), c["type"].get<std::string>(),
                              c["count"].get<std::uint64_t>());
        if (c.contains("unit")) report += fmt::format("  unit {}", c["unit"].get<std::string>());
        if (c.contains("sample_rate_hz")) report += fmt::format("  {:.10g} Hz", c["sample_rate_hz"].get<double>());
        if (c.contains("mean")) {
          report += fmt::format("  mean {:.8g} sd {:.6g} min {:.8g} max {:.8g}", c["mean"].get<double>(),
                                c.value("standard_deviation", 0.0), c["min"].get<double>(), c["max"].get<double>());
        }
        report += "\n";
        continue;
      }
      report += fmt::format("  {:<16} mean {:<14.8g} sd {:<12.6g} min {:<14.8g} max {:.8g}\n",
                            c["name"].get<std::string>(), c["mean"].get<double>(),
                            c.value("standard_deviation", 0.0), c["min"].get<double>(), c["max"].get<double>());
    }
    if (!time_report.is_null()) {
      json["time_stamps"] = time_report;
      report += fmt::format("time stamps: sample interval {:.6g}, {} gap(s), {} segment(s), {} sample(s) interpolated\n",
                            time_report["sample_interval"].get<double>(), time_report["gaps"].size(),
                            time_report["segments"].size(), time_report["interpolated_samples"].get<std::size_t>());
      for (const auto& gap : time_report["gaps"]) {
        report += fmt::format("  gap before line {}: {:.10g} to {:.10g}, {} sample(s) missing\n",
                              gap["line"].get<std::size_t>(), gap["time_before"].get<double>(),
                              gap["time_after"].get<double>(), gap["missing_samples"].get<std::size_t>());
      }
    }
    for (const auto& warning : warnings) {
      fmt::print(stderr, "inertest: warning: {}: {}\n", arguments->file, warning.get<std::string>());
    }
    print_result(json, report, arguments->json);
    return 0;
  };
}

const bool registered = register_command("inspect", setup);

}  // namespace
}  // namespace inertest::cli

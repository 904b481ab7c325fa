#include "inertest/allan/allan_channels.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <fmt/format.h>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>
#include <type_traits>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/core/units.h"
#include "inertest/io/time_stamps.h"

namespace inertest {

namespace {

// The unit `units` gives each channel (by its name, or the bare unit of the channels not named),
// nullopt where it gives none. Throws ParameterError as channel_options.
std::vector<std::optional<std::string>> given_units(const std::vector<std::string>& names,
                                                    const std::vector<std::string>& selectors, std::string_view units) {
  std::optional<std::string> fallback;
  std::map<std::size_t, std::string> named;
  bool bare_seen = false;
  // Split as the record readers split a line: blanks around each part trimmed.
  for (const TextField& item : split_text_line(units, ',', "input_unit", 1)) {
    if (item.text.empty()) continue;
    const std::vector<TextField> parts = split_text_line(item.text, '=', "input_unit", 1);
    if (parts.size() == 1) {
      if (bare_seen) {
        throw ParameterError("input_unit", "input_unit gives two units without a channel name ('" + *fallback +
                                               "', '" + item.text + "')");
      }
      bare_seen = true;
      check_parameter("input_unit", [&] { Unit::parse(item.text); });
      fallback = item.text;
      continue;
    }
    if (parts.size() != 2) throw ParameterError("input_unit", "input_unit has '" + item.text + "', which is not NAME=UNIT");
    const std::string& name = parts[0].text;
    const std::string& unit = parts[1].text;
    std::size_t channel = names.size();
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] == name || (i < selectors.size() && selectors[i] == name)) channel = i;
    }
    if (channel == names.size()) {
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
      throw ParameterError("input_unit",
                           "input_unit names '" + name + "', which is not a channel asked for (" + list + ")");
    }
    if (named.contains(channel)) {
      throw ParameterError("input_unit", "input_unit gives channel '" + names[channel] + "' twice");
    }
    check_parameter("input_unit", [&] { Unit::parse(unit); });
    named[channel] = unit;
  }
  std::vector<std::optional<std::string>> given(names.size(), fallback);
  for (const auto& [channel, unit] : named) given[channel] = unit;
  return given;
}

}  // namespace

std::vector<AllanOptions> channel_options(const AllanOptions& common, const std::vector<std::string>& names,
                                          const std::vector<std::string>& selectors, std::string_view units) {
  const std::vector<std::optional<std::string>> given = given_units(names, selectors, units);
  std::vector<AllanOptions> options(names.size(), common);
  for (std::size_t i = 0; i < names.size(); ++i) options[i].input_unit = given[i].value_or(common.input_unit);
  return options;
}

namespace {

// The unit of a channel of raw output (allan_variance_of_channels_in_file's raw_output) that states
// `stated`: a rate or an acceleration is no raw output for K to divide (its deg/s were divided by K
// again and labelled deg/s), another unit (pulse/s) is the output K turns into common.input_unit.
std::string raw_output_unit(const SourceLocation& where, const std::string& stated_where, const std::string& stated,
                            const AllanOptions& common) {
  if (sensor_kind_of(stated) == SensorKind::kOther) return common.input_unit;
  throw Error(where, fmt::format("the unit {} {} is a rate or an acceleration, not a raw output: scale_factor divides a "
                                 "raw output by K (leave it out, or give input_unit)",
                                 stated, stated_where));
}

// allan_variance_of_channels on columns it may overwrite (std::span<double>: each analysed in
// place, allan_variance_in_place) or not (std::span<const double>).
template <typename Sample>
AllanChannels analyse_channels(const std::vector<std::span<Sample>>& columns, const std::vector<std::string>& names,
                               const std::vector<AllanOptions>& options) {
  if (columns.empty()) throw Error("no channel to analyse");
  if (names.size() != columns.size() || options.size() != columns.size()) {
    throw Error("one name and one set of options per channel are needed");
  }
  for (const auto& column : columns) {
    if (column.size() != columns.front().size()) throw Error("the channels differ in length");
  }
  // Each channel's result is under its name: a second one of a name would hide the first.
  std::set<std::string> seen;
  for (const std::string& name : names) {
    if (!seen.insert(name).second) throw Error("channel '" + name + "' is asked for twice");
  }
  for (const AllanOptions& o : options) o.validate();
  // Channels side by side, each engine on one thread (the engine's sums do not depend on its thread
  // count, so neither do the results); a single channel keeps all the workers.
  const std::size_t threads = std::min(columns.size(), options.front().worker_count);
  AllanChannels result;
  result.channels.resize(columns.size());
  std::vector<std::exception_ptr> failures(columns.size());
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t i = next++; i < columns.size(); i = next++) {
      try {
        AllanOptions own = options[i];
        if (threads > 1) own.worker_count = 1;
        if constexpr (std::is_const_v<Sample>) {
          result.channels[i] = {names[i], allan_variance(columns[i], own)};
        } else {
          result.channels[i] = {names[i], allan_variance_in_place(columns[i], own)};
        }
      } catch (...) {
        failures[i] = std::current_exception();
      }
    }
  };
  {
    std::vector<std::jthread> pool;
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
  }
  for (std::size_t i = 0; i < failures.size(); ++i) {
    if (!failures[i]) continue;
    try {
      std::rethrow_exception(failures[i]);
    } catch (const Error& e) {
      const std::string message = "channel " + names[i] + ": " + e.message();
      if (e.location()) throw Error(*e.location(), message);
      throw Error(message);
    }
  }
  return result;
}

}  // namespace

AllanChannels allan_variance_of_channels(const std::vector<std::span<const double>>& columns,
                                         const std::vector<std::string>& names,
                                         const std::vector<AllanOptions>& options) {
  return analyse_channels(columns, names, options);
}

AllanChannels allan_variance_of_channels_in_file(const RateRecordSource& given_source,
                                                 const std::vector<ColumnSelector>& columns, std::string_view units,
                                                 const AllanOptions& common, bool raw_output,
                                                 const ProgressCallback& progress) {
  if (columns.empty()) throw Error("no channel to analyse: give --columns");
  RateRecordSource source = given_source;
  source.format = resolve_rate_record_format(given_source);
  std::vector<std::string> selectors;
  // As given: "2" or "gx".
  for (const ColumnSelector& column : columns) {
    selectors.push_back(column.index > 0 ? std::to_string(column.index) : column.name);
  }
  if (source.format == RateRecordFormat::kBinary) {
    throw Error(SourceLocation{source.path, 0, 0}, "a raw binary record holds one channel: use --column, not --columns");
  }
  if (source.format == RateRecordFormat::kCsv) {
    if (progress) progress("reading " + source.path, 0.0);
    TextTableOptions text;
    text.record_row_lines = false;
    text.columns = columns;
    TextTable table = read_text_table(source.path, text);
    check_time_column_span(source.path, table.rows());  // a gap in its stamps, a rate that changes
    std::vector<std::string> names;
    std::vector<std::span<double>> spans;  // read only to be analysed: in place
    for (std::size_t i = 0; i < table.columns.size(); ++i) {
      names.push_back(table.names[i].empty() ? selectors[i] : table.names[i]);
      spans.emplace_back(table.columns[i]);
    }
    // A unit a column's header states ("gx [deg/s]") is its samples' unit, as a channel's stored one.
    std::vector<AllanOptions> options = channel_options(common, names, selectors, units);
    const std::vector<std::optional<std::string>> given = given_units(names, selectors, units);
    const SourceLocation header{source.path, table.header_line, 0};
    for (std::size_t i = 0; i < names.size(); ++i) {
      std::optional<std::string> stated;
      try {
        stated = unit_stated_in_name(names[i], header);
      } catch (const Error&) {
        if (given[i]) continue;  // a header's unit inertest does not read: the one given stands
        throw;
      }
      if (stated) {
        const std::string stated_where = fmt::format("the header states for column '{}'", names[i]);
        options[i].input_unit = raw_output ? raw_output_unit(header, stated_where, *stated, common)
                                           : *resolve_stated_unit(header, stated_where, *stated, given[i]);
      }
    }
    return analyse_channels(spans, names, options);
  }
  // A record of named channels stores each channel apart: each is streamed once, in turn, at the
  // rate and in the unit given or, where none is given, those it stores for the channel.
  const std::optional<ChannelRecordFormat> channel_format = channel_record_format_of(source.format);
  std::vector<std::string> names;
  std::vector<AllanOptions> options;
  {
    const std::unique_ptr<ChannelRecord> record = open_channel_record(source.path, *channel_format);
    std::vector<std::size_t> indices;
    for (const ColumnSelector& column : columns) {
      indices.push_back(record->find(column));
      names.push_back(record->channels()[indices.back()].name);
    }
    const std::vector<std::optional<std::string>> given = given_units(names, selectors, units);
    const std::optional<double> rate = common.sample_rate_hz > 0.0 ? std::optional(common.sample_rate_hz) : std::nullopt;
    options.assign(names.size(), common);
    for (std::size_t i = 0; i < names.size(); ++i) {
      options[i].sample_rate_hz = resolve_sample_rate(*record, indices[i], rate);
      const std::optional<std::string> stored = resolve_unit(*record, indices[i], raw_output ? std::nullopt : given[i]);
      options[i].input_unit =
          !stored ? common.input_unit
          : raw_output ? raw_output_unit(SourceLocation{source.path, 0, 0}, fmt::format("stored for channel '{}'", names[i]),
                                         *stored, common)
                       : *stored;
    }
  }
  AllanChannels result;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    source.column = columns[i];
    result.channels.push_back({names[i], allan_variance_of_file(source, options[i], progress)});
  }
  return result;
}

nlohmann::json AllanChannels::to_json() const {
  nlohmann::json json = nlohmann::json::object();
  for (const AllanChannel& channel : channels) json[channel.name] = channel.result.to_json();
  return {{"procedure", "allan_variance"}, {"clause", kAllanClause}, {"channels", json}};
}

std::string AllanChannels::report() const {
  std::string text;
  for (const AllanChannel& channel : channels) {
    text += fmt::format("{}== channel {} ==\n{}", text.empty() ? "" : "\n", channel.name, channel.result.report());
  }
  return text;
}

}  // namespace inertest

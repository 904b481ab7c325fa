#include "inertest/io/output_record.h"

#include <algorithm>

#include <cmath>

#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/core/units.h"
#include "inertest/io/binary_record.h"
#include "inertest/io/channel_record.h"
#include "inertest/io/text_table.h"
#include "inertest/io/time_stamps.h"

namespace inertest {
namespace {

void require_samples(const std::string& path, std::size_t count, std::size_t minimum_samples) {
  if (count < minimum_samples) {
    throw Error(SourceLocation{path, 0, 0},
                fmt::format("the record holds {} sample(s); at least {} are needed", count, minimum_samples));
  }
}

ColumnSelector selector_or(const std::string& text, std::size_t fallback_index) {
  if (text.empty()) return ColumnSelector{"", fallback_index};
  return ColumnSelector::parse(text);
}

bool is_text(const std::string& format) { return format.empty() || format == "auto" || format == "csv"; }

// The format of a record of named channels: named, or found by its magic bytes under "" and "auto".
std::optional<ChannelRecordFormat> channel_format_of(const OutputRecordSource& source) {
  if (source.format == "mat") return ChannelRecordFormat::kMat;
  if (source.format == "hdf5") return ChannelRecordFormat::kHdf5;
  if (source.format == "tdms") return ChannelRecordFormat::kTdms;
  if (source.format.empty() || source.format == "auto") return detect_channel_record_format(source.path);
  return std::nullopt;
}

std::optional<ColumnSelector> channel_selector(const std::string& text) {
  if (text.empty()) return std::nullopt;
  return ColumnSelector::parse(text);
}

}  // namespace

void check_output_record_format(const std::string& format) {
  if (is_text(format) || format == "mat" || format == "hdf5" || format == "tdms") return;
  try {
    BinaryFormat::parse(format);
  } catch (const Error&) {
    throw Error(fmt::format("unknown record format '{}' (expected auto, csv, mat, hdf5, tdms, or f64, f32, i32 or i16, "
                            "optionally with le or be)",
                            format));
  }
}

std::vector<double> read_output_record(const OutputRecordSource& source, std::size_t minimum_samples) {
  if (const std::optional<ChannelRecordFormat> channel_format = channel_format_of(source)) {
    const std::unique_ptr<ChannelRecord> record = open_channel_record(source.path, *channel_format);
    std::vector<double> samples = read_channel(*record, record->find(channel_selector(source.column)));
    require_samples(source.path, samples.size(), minimum_samples);
    return samples;
  }
  if (!is_text(source.format)) {
    if (!source.column.empty()) {  // it was ignored: interleaved channels were read as one
      throw Error(SourceLocation{source.path, 0, 0},
                  fmt::format("a raw {} record holds one channel: --column (plan key `column`) does not apply",
                              source.format));
    }
    std::vector<double> samples = read_binary_record(source.path, BinaryFormat::parse(source.format));
    require_samples(source.path, samples.size(), minimum_samples);
    return samples;
  }
  TextTableOptions options;
  if (!source.column.empty()) options.columns = {ColumnSelector::parse(source.column)};
  options.record_row_lines = false;
  options.minimum_rows = minimum_samples;
  TextTable table = read_text_table(source.path, options);
  if (table.columns.size() == 1) return std::move(table.columns.front());
  // Several columns and none chosen: the one headed "output", else the choice is the user's (the
  // first column of a time,output record is the time: taking it silently gave its mean as a bias).
  const auto output = std::find(table.names.begin(), table.names.end(), "output");
  if (output != table.names.end()) return std::move(table.columns[static_cast<std::size_t>(output - table.names.begin())]);
  const std::size_t first_line = table.header_line != 0 ? table.header_line : table.first_data_line;
  throw Error(SourceLocation{source.path, first_line, 1},
              fmt::format("the record has {} columns{}: choose the output with --column (plan key `column`)",
                          table.columns.size(), table.header_line != 0 ? " (" + fmt::format("{}", fmt::join(table.names, ", ")) + ")" : ""));
}

TimedRecord read_timed_record(const OutputRecordSource& source, std::optional<double> sample_rate_hz,
                              const std::string& time_column, std::size_t minimum_samples) {
  TimedRecord record;
  if (const std::optional<ChannelRecordFormat> channel_format = channel_format_of(source)) {
    const std::unique_ptr<ChannelRecord> file = open_channel_record(source.path, *channel_format);
    const std::size_t output = file->find(channel_selector(source.column));
    if (!sample_rate_hz && !file->channels()[output].sample_rate_hz && !time_column.empty()) {
      const std::size_t time_channel = file->find(ColumnSelector::parse(time_column));
      record.time_s = read_channel(*file, time_channel);
      const ChannelInfo& time_info = file->channels()[time_channel];
      const double seconds = with_file_context(source.path, [&] { return seconds_per_time_stamp(time_info.name, time_info.unit); });
      for (double& stamp : record.time_s) stamp *= seconds;
      record.output = read_channel(*file, output);
      if (record.time_s.size() != record.output.size()) {
        throw Error(SourceLocation{source.path, 0, 0},
                    fmt::format("time channel '{}' holds {} samples, output channel '{}' {}", time_column,
                                record.time_s.size(), file->channels()[output].name, record.output.size()));
      }
      require_samples(source.path, record.output.size(), minimum_samples);
      for (std::size_t i = 1; i < record.time_s.size(); ++i) {
        if (!(record.time_s[i] > record.time_s[i - 1])) {
          throw Error(SourceLocation{source.path, 0, 0},
                      fmt::format("time channel '{}', sample {}: time {} s does not follow the previous time {} s: "
                                  "times must increase",
                                  time_column, i + 1, record.time_s[i], record.time_s[i - 1]));
        }
      }
      return record;
    }
    const double rate = resolve_sample_rate(*file, output, sample_rate_hz);
    record.output = read_channel(*file, output);
    require_samples(source.path, record.output.size(), minimum_samples);
    record.time_s.resize(record.output.size());
    for (std::size_t i = 0; i < record.output.size(); ++i) record.time_s[i] = static_cast<double>(i + 1) / rate;
    return record;
  }
  if (!sample_rate_hz && !is_text(source.format)) sample_rate_hz = source.instrument_sample_rate_hz;
  if (sample_rate_hz) {
    if (!(*sample_rate_hz > 0.0)) throw Error(fmt::format("sample rate must be positive, got {} Hz", *sample_rate_hz));
    if (is_text(source.format)) check_sample_rate_against_time_column(source.path, *sample_rate_hz);
    record.output = read_output_record(source, minimum_samples);
    // Times made from the rate: a gap in the record's own stamps, or a rate that changes, would shift them.
    if (is_text(source.format)) check_time_column_span(source.path, record.output.size());
    record.time_s.resize(record.output.size());
    for (std::size_t i = 0; i < record.output.size(); ++i) {
      record.time_s[i] = static_cast<double>(i + 1) / *sample_rate_hz;
    }
    return record;
  }
  if (!is_text(source.format)) {
    throw Error(SourceLocation{source.path, 0, 0},
                "a binary record has no time column: give the sample rate (--rate; in a plan sample_rate_hz in the "
                "step or in [instrument])");
  }
  TextTableOptions options;
  options.columns = {selector_or(time_column, 1), selector_or(source.column, 2)};
  options.minimum_rows = minimum_samples;
  TextTable table = read_text_table(source.path, options);
  record.time_s = take_time_column_s(table, 0);
  record.output = std::move(table.columns[1]);
  return record;
}

double record_sample_rate(const OutputRecordSource& source, double given) {
  const std::optional<double> rate = given != 0.0 ? std::optional<double>(given) : std::nullopt;
  const std::optional<ChannelRecordFormat> channel_format = channel_format_of(source);
  if (!channel_format) {
    // A text record's time column whose name states its unit (time_s) gives its rate, as a stored one.
    const std::optional<RecordTimeColumn> time =
        is_text(source.format) ? find_record_time_column(source.path) : std::nullopt;
    if (!rate && time && time->unit_stated) return time->sample_rate_hz();
    if (!rate) {
      throw ParameterError("sample_rate_hz", "sample_rate_hz is needed: the record stores no sample rate (a text record "
                                             "gives it by a time column whose name states its unit, e.g. time_s)");
    }
    if (is_text(source.format)) check_sample_rate_against_time_column(source.path, *rate);
    return *rate;
  }
  const std::unique_ptr<ChannelRecord> file = open_channel_record(source.path, *channel_format);
  return resolve_sample_rate(*file, file->find(channel_selector(source.column)), rate);
}

std::optional<std::string> record_unit(const OutputRecordSource& source, const std::optional<std::string>& given) {
  const std::optional<ChannelRecordFormat> channel_format = channel_format_of(source);
  if (!channel_format && is_text(source.format)) return resolve_text_unit(source.path, channel_selector(source.column), given);
  if (!channel_format) return given;
  const std::unique_ptr<ChannelRecord> file = open_channel_record(source.path, *channel_format);
  return resolve_unit(*file, file->find(channel_selector(source.column)), given);
}

void set_record_readers(ProcedureCall& call, const OutputRecordSource& source, std::size_t minimum_samples,
                        std::optional<double> sample_rate_hz, const std::string& time_column) {
  // The source of one file; its errors without a place named at the file.
  const auto of_file = [source](const std::string& file, const auto& work) {
    OutputRecordSource record = source;
    record.path = file;
    return with_file_context(file, [&] { return work(record); });
  };
  call.read_record = [of_file, minimum_samples](const std::string& file) {
    return of_file(file, [&](const OutputRecordSource& record) { return read_output_record(record, minimum_samples); });
  };
  call.read_timed_record = [of_file, minimum_samples, sample_rate_hz, time_column](const std::string& file) {
    return of_file(file, [&](const OutputRecordSource& record) {
      return read_timed_record(record, sample_rate_hz, time_column, minimum_samples);
    });
  };
  call.record_sample_rate = [of_file](const std::string& file, double given) {
    return of_file(file, [&](const OutputRecordSource& record) { return record_sample_rate(record, given); });
  };
  call.record_unit = [of_file](const std::string& file, const std::optional<std::string>& given) {
    return of_file(file, [&](const OutputRecordSource& record) { return record_unit(record, given); });
  };
}

void read_pulse_counts_as_rates(ProcedureCall& call, const ProcedureSpec& spec,
                                const std::function<bool(const InputSpec&)>& given,
                                std::optional<double> sample_rate_hz) {
  const auto output_unit = call.parameters.find("output_unit");
  if (output_unit == call.parameters.end() || !output_unit->is_string() ||
      !counts_pulses(output_unit->get<std::string>())) {
    return;
  }
  bool records = false;
  bool files = false;
  for (const InputSpec& input : spec.inputs) {
    if (input.kind == InputKind::value_or_record || !given(input)) continue;
    files = true;
    records = records || input.records;
    call.pulse_counts = call.pulse_counts || input.raw_samples;
  }
  if (!files) return;
  call.parameters["output_unit"] = output_unit_as_rate(output_unit->get<std::string>());
  if (!records) return;
  const auto given_rate = call.parameters.find("sample_rate_hz");
  const double rate = sample_rate_hz                                                   ? *sample_rate_hz
                      : given_rate != call.parameters.end() && given_rate->is_number() ? given_rate->get<double>()
                                                                                       : 0.0;
  const auto no_rate = [](const std::string& file) {
    return Error(SourceLocation{file, 0, 0},
                 "the output unit pulse counts pulses per sample interval, and the record stores no sample rate to "
                 "make them pulse/s: give the sample rate (--rate; sample_rate_hz), or the record in pulse/s");
  };
  call.read_record = [read = call.read_record, sample_rate = call.record_sample_rate, rate,
                      no_rate](const std::string& file) {
    double rate_hz = 0.0;
    try {
      rate_hz = sample_rate(file, rate);  // before the samples: a record of 10^9 is not read for nothing
    } catch (const ParameterError&) {
      throw no_rate(file);
    }
    std::vector<double> samples = read(file);
    pulse_counts_as_rates(samples, rate_hz);
    return samples;
  };
  call.read_timed_record = [read = call.read_timed_record, rate, no_rate](const std::string& file) {
    TimedRecord record = read(file);
    if (rate == 0.0 && record.time_s.size() < 2) throw no_rate(file);  // one time stamp is no interval
    pulse_counts_as_rates(record, rate > 0.0 ? std::optional<double>(rate) : std::nullopt);
    return record;
  };
}

std::string output_unit_as_rate(const std::string& output_unit) {
  return counts_pulses(output_unit) ? "pulse/s" : output_unit;
}

void pulse_counts_as_rates(std::span<double> outputs, double sample_rate_hz) {
  for (double& count : outputs) count *= sample_rate_hz;
}

void pulse_counts_as_rates(TimedRecord& record, std::optional<double> sample_rate_hz) {
  pulse_counts_as_rates(record.output, sample_rate_hz ? *sample_rate_hz : mean_sample_rate_hz(record.time_s));
}

double mean_sample_rate_hz(std::span<const double> time_s) {
  if (time_s.size() < 2) throw Error("one time stamp has no sample interval");
  const std::size_t steps = time_s.size() - 1;
  const double span = time_s.back() - time_s.front();
  // Gaps are a logger's dropped samples: rare (at most 1 % of the steps), each a whole number of
  // intervals (within a quarter, and the stamps' rounding where they are coarse: 0.8 Hz in s).
  // Stamps that are jittered or sent in bursts have many long steps, or long steps of no whole
  // number, and keep the steps over the span, which telescope to the right rate.
  const TimeGaps found = find_time_gaps(time_s, {}, TimeStampOptions{});
  const std::vector<TimeGap>& gaps = found.gaps;
  if (gaps.empty() || gaps.size() * 100 > steps) return static_cast<double>(steps) / span;
  double gap_span = 0.0;
  for (const TimeGap& gap : gaps) gap_span += gap.time_after - gap.time_before;
  const double interval = (span - gap_span) / static_cast<double>(steps - gaps.size());
  for (const TimeGap& gap : gaps) {
    const double intervals = (gap.time_after - gap.time_before) / interval;
    if (std::abs(intervals - std::round(intervals)) > 0.25 + found.stamp_quantum / interval) {
      return static_cast<double>(steps) / span;
    }
  }
  return 1.0 / interval;
}

void require_raw_output(const ProcedureCall& call, const std::string& file, const std::string& output_unit,
                        const std::string& instead) {
  std::optional<std::string> stored;
  try {
    stored = call.record_unit(file, std::nullopt);
  } catch (const Error&) {
    return;  // a stored unit inertest does not know is no rate or acceleration it could convert
  }
  if (!stored) return;
  const Dimension dimension = Unit::parse(*stored).dimension();
  if (dimension != Unit::parse("rad/s").dimension() && dimension != Unit::parse("m/s^2").dimension()) return;
  if (same_unit(output_unit, *stored)) return;  // the instrument's own output
  throw Error(SourceLocation{file, 0, 0},
              fmt::format("the record stores its samples in {}, not the instrument's {} that the scale factor K "
                          "divides: {}",
                          *stored, output_unit.empty() || output_unit == "1" ? "raw output" : "output in " + output_unit,
                          instead));
}

}  // namespace inertest

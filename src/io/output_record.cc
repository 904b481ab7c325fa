#include "inertest/io/output_record.h"

#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/io/binary_record.h"
#include "inertest/io/text_table.h"

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

}  // namespace

std::vector<double> read_output_record(const OutputRecordSource& source, std::size_t minimum_samples) {
  if (!source.format.empty()) {
    std::vector<double> samples = read_binary_record(source.path, BinaryFormat::parse(source.format));
    require_samples(source.path, samples.size(), minimum_samples);
    return samples;
  }
  TextTableOptions options;
  options.columns = {selector_or(source.column, 1)};
  options.record_row_lines = false;
  options.minimum_rows = minimum_samples;
  TextTable table = read_text_table(source.path, options);
  return std::move(table.columns.front());
}

TimedRecord read_timed_record(const OutputRecordSource& source, std::optional<double> sample_rate_hz,
                              const std::string& time_column, std::size_t minimum_samples) {
  TimedRecord record;
  if (sample_rate_hz) {
    if (!(*sample_rate_hz > 0.0)) throw Error(fmt::format("sample rate must be positive, got {} Hz", *sample_rate_hz));
    record.output = read_output_record(source, minimum_samples);
    record.time_s.resize(record.output.size());
    for (std::size_t i = 0; i < record.output.size(); ++i) {
      record.time_s[i] = static_cast<double>(i + 1) / *sample_rate_hz;
    }
    return record;
  }
  if (!source.format.empty()) {
    throw Error(SourceLocation{source.path, 0, 0},
                "a binary record has no time column: give the sample rate (--rate / sample_rate_hz)");
  }
  TextTableOptions options;
  options.columns = {selector_or(time_column, 1), selector_or(source.column, 2)};
  options.minimum_rows = minimum_samples;
  TextTable table = read_text_table(source.path, options);
  for (std::size_t i = 1; i < table.rows(); ++i) {
    if (!(table.columns[0][i] > table.columns[0][i - 1])) {
      throw Error(SourceLocation{source.path, table.row_lines[i], 0},
                  fmt::format("time {} s does not follow the previous time {} s: times must increase",
                              table.columns[0][i], table.columns[0][i - 1]));
    }
  }
  record.time_s = std::move(table.columns[0]);
  record.output = std::move(table.columns[1]);
  return record;
}

}  // namespace inertest

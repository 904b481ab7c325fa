#include "inertest/io/procedure_inputs.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <string_view>

#include "inertest/core/units.h"
#include "inertest/io/mapped_file.h"
#include "inertest/io/text_table.h"
#include "inertest/io/time_stamps.h"

namespace inertest {
namespace {

TextTable read_columns(const std::string& path, std::vector<std::string> names) {
  TextTableOptions options;
  for (const auto& name : names) options.columns.push_back(ColumnSelector::parse(name));
  return read_text_table(path, options);
}

// Rethrows a procedure's error with the file it came from.
[[noreturn]] void rethrow_in(const std::string& path, const Error& e) { throw Error(SourceLocation{path, 0, 0}, e.message()); }

}  // namespace

std::vector<ListedFile> read_file_listing(const std::string& listing, const std::string& key_column,
                                          const std::string& file_column) {
  const MappedFile file(listing);
  const std::string_view text = file.text();
  const std::filesystem::path directory = std::filesystem::path(listing).parent_path();
  std::vector<ListedFile> rows;
  std::size_t key_index = 0;
  std::size_t file_index = 0;
  std::size_t columns = 0;
  bool have_header = false;
  for (const auto& [line_number, cells] : split_text_cells(text, listing)) {
    if (!have_header) {
      bool found_key = false;
      bool found_file = false;
      for (std::size_t c = 0; c < cells.size(); ++c) {
        if (cells[c].text == key_column) key_index = c, found_key = true;
        if (cells[c].text == file_column) file_index = c, found_file = true;
      }
      if (!found_key || !found_file) {
        throw Error(SourceLocation{listing, line_number, 1},
                    fmt::format("expected a header row naming the columns '{}' and '{}'", key_column, file_column));
      }
      columns = cells.size();
      have_header = true;
      continue;
    }
    if (cells.size() != columns) {
      throw Error(SourceLocation{listing, line_number, 1},
                  fmt::format("{} columns, but the header has {}", cells.size(), columns));
    }
    const TextField& key = cells[key_index];
    ListedFile row;
    const auto parsed = std::from_chars(key.text.data(), key.text.data() + key.text.size(), row.key);
    if (key.text.empty() || parsed.ec != std::errc() || parsed.ptr != key.text.data() + key.text.size() ||
        !std::isfinite(row.key)) {
      throw Error(SourceLocation{listing, line_number, key.column},
                  fmt::format("expected a number in column '{}', found '{}'", key_column, key.text));
    }
    const TextField& name = cells[file_index];
    if (name.text.empty()) {
      throw Error(SourceLocation{listing, line_number, name.column}, "expected a file name in column '" + file_column + "'");
    }
    std::filesystem::path path(std::string(name.text));
    if (path.is_relative()) path = directory / path;
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) {
      throw Error(SourceLocation{listing, line_number, name.column},
                  fmt::format("data file '{}' not found (looked for {})", name.text, path.string()));
    }
    row.path = path.lexically_normal().string();
    row.where = {listing, line_number, key.column};
    rows.push_back(std::move(row));
  }
  if (!have_header) throw Error(SourceLocation{listing, 0, 0}, "empty listing: expected a header row and data rows");
  if (rows.empty()) throw Error(SourceLocation{listing, 0, 0}, "the listing names no files");
  return rows;
}

std::vector<ScaleFactorPoint> read_scale_factor_points(const std::string& path) {
  TextTableOptions read;
  read.columns = {ColumnSelector{"rate"}, ColumnSelector{"output"}};
  read.header = TextTableOptions::Header::kPresent;
  const TextTable table = read_text_table(path, read);
  std::vector<ScaleFactorPoint> points(table.rows());
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = {table.columns[0][i], table.columns[1][i]};
  return points;
}

std::vector<ScaleFactorPoint> read_scale_factor_record(const std::string& path, const std::string& rate_column,
                                                       const std::string& output_column,
                                                       const RateSegmentOptions& options) {
  TextTableOptions read;
  read.columns = {ColumnSelector::parse(rate_column), ColumnSelector::parse(output_column)};
  read.record_row_lines = false;
  check_sample_rate_against_time_column(path, options.timing.sample_rate_hz);
  const TextTable table = read_text_table(path, read);
  try {
    const std::vector<RateSegment> segments = segment_by_rate(table.columns[0], table.columns[1], options);
    return scale_factor_points(segments);
  } catch (const Error& e) {
    rethrow_in(path, e);
  }
}

std::vector<ScaleFactorPoint> read_scale_factor_point_records(std::span<const ListedFile> points,
                                                              const std::string& output_column,
                                                              const RecordTiming& timing) {
  timing.validate();
  std::vector<ScaleFactorPoint> result;
  TextTableOptions read;
  read.columns = {ColumnSelector::parse(output_column)};
  read.record_row_lines = false;
  for (const auto& point : points) {
    check_sample_rate_against_time_column(point.path, timing.sample_rate_hz);
    const TextTable table = read_text_table(point.path, read);
    try {
      result.push_back({point.key, record_mean(table.columns[0], timing)});  // eq. (1)
    } catch (const Error& e) {
      rethrow_in(point.path, e);
    }
  }
  return result;
}

std::vector<FrequencyResponsePoint> read_frequency_response(const std::string& path) {
  TextTableOptions read;
  read.columns = {ColumnSelector{"freq_hz"}, ColumnSelector{"gain"}, ColumnSelector{"phase_deg"}};
  read.header = TextTableOptions::Header::kPresent;
  const TextTable table = read_text_table(path, read);
  std::vector<FrequencyResponsePoint> points;
  for (std::size_t i = 0; i < table.rows(); ++i) {
    const double f = table.columns[0][i];
    const SourceLocation where{path, table.row_lines.empty() ? 0 : table.row_lines[i], 0};
    if (f <= 0.0) throw Error(where, fmt::format("frequency {} Hz is not positive", f));
    if (i > 0 && !(f > table.columns[0][i - 1])) {
      throw Error(where, fmt::format("frequency {} Hz is not above the one before ({} Hz); the frequencies must "
                                     "increase",
                                     f, table.columns[0][i - 1]));
    }
    if (table.columns[1][i] <= 0.0) throw Error(where, fmt::format("gain {} is not positive", table.columns[1][i]));
    points.push_back({f, table.columns[1][i], table.columns[2][i] * constants::kDegree});
  }
  return points;
}

std::vector<ListedFile> listed_files(std::span<const RunInput> runs) {
  std::vector<ListedFile> files;
  for (const RunInput& run : runs) files.push_back({run.number, run.file, run.where});
  return files;
}

void check_increasing_frequencies(std::span<const ListedFile> runs) {
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto& run = runs[i];
    if (run.key <= 0.0) throw Error(run.where, fmt::format("frequency {} Hz is not positive", run.key));
    if (i > 0 && !(run.key > runs[i - 1].key)) {
      throw Error(run.where, fmt::format("frequency {} Hz is not above the one before ({} Hz); the frequencies must "
                                         "increase",
                                         run.key, runs[i - 1].key));
    }
  }
}

std::vector<AngularVibrationRecord> read_angular_vibration_records(std::span<const ListedFile> runs,
                                                                   const std::string& time_column,
                                                                   const std::string& output_column,
                                                                   const std::string& angle_column) {
  check_increasing_frequencies(runs);
  std::vector<AngularVibrationRecord> records;
  for (const ListedFile& run : runs) {
    TextTable table = read_columns(run.path, {time_column, output_column, angle_column});
    AngularVibrationRecord record;
    record.frequency_hz = run.key;
    // A time going back, or the record pasted twice, was accepted silently.
    record.time_s = take_time_column_s(table, 0);
    record.output = std::move(table.columns[1]);
    record.angle = std::move(table.columns[2]);
    record.source = run.path;
    records.push_back(std::move(record));
  }
  return records;
}

}  // namespace inertest

#include "inertest/misalignment/misalignment_files.h"

#include <fmt/format.h>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <string_view>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/io/mapped_file.h"
#include "inertest/io/output_record.h"
#include "inertest/io/text_table.h"
#include "inertest/misalignment/revolution_average.h"

namespace inertest {
namespace {

TextTable read_with_header(const std::string& path) {
  TextTableOptions read;
  read.header = TextTableOptions::Header::kPresent;
  return read_text_table(path, read);
}

double parse_number(const TextField& field, const SourceLocation& line_location, const char* name) {
  double value = 0.0;
  const char* first = field.text.data();
  const char* last = first + field.text.size();
  if (!field.text.empty() && *first == '+') ++first;
  const auto [end, error] = std::from_chars(first, last, value);
  if (error != std::errc() || end != last || field.text.empty()) {
    throw Error(SourceLocation{line_location.file, line_location.line, field.column},
                fmt::format("{} '{}' is not a number", name, field.text));
  }
  return value;
}

}  // namespace

std::vector<GyroMisalignmentRow> read_gyro_misalignment_positions(const std::string& path) {
  const TextTable table = read_with_header(path);
  const auto& alpha = table.column("alpha_deg");
  const auto& beta = table.column("beta_deg");
  const auto& rate = table.column("rate_dps");
  const auto& output = table.column("output");
  std::vector<GyroMisalignmentRow> rows(table.rows());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    rows[i] = {alpha[i], beta[i], rate[i], output[i], table.row_lines.empty() ? 0 : table.row_lines[i]};
  }
  return rows;
}

std::vector<GyroMisalignmentRow> read_gyro_misalignment_records(const std::string& listing_path, bool pulse_counts) {
  const MappedFile listing(listing_path);
  const std::filesystem::path directory = std::filesystem::path(listing_path).parent_path();
  const std::string_view text = listing.text();
  const std::vector<std::string> names = {"alpha_deg", "beta_deg", "rate_dps", "file"};
  std::vector<std::size_t> index_of;  // field index of each name
  std::vector<GyroMisalignmentRow> rows;
  for (const auto& [line_number, fields] : split_text_cells(text, listing_path)) {
    const SourceLocation where{listing_path, line_number, 0};
    if (index_of.empty()) {
      for (const std::string& name : names) {
        const auto found = std::find_if(fields.begin(), fields.end(), [&](const TextField& f) { return f.text == name; });
        if (found == fields.end()) {
          throw Error(where, fmt::format("record listing: the header has no column '{}'; expected "
                                         "alpha_deg,beta_deg,rate_dps,file",
                                         name));
        }
        index_of.push_back(static_cast<std::size_t>(found - fields.begin()));
      }
      continue;
    }
    if (fields.size() <= *std::max_element(index_of.begin(), index_of.end())) {
      throw Error(where, fmt::format("record listing: {} field(s), the header has more", fields.size()));
    }
    GyroMisalignmentRow row;
    row.alpha_deg = parse_number(fields[index_of[0]], where, "alpha_deg");
    row.beta_deg = parse_number(fields[index_of[1]], where, "beta_deg");
    row.rate_dps = parse_number(fields[index_of[2]], where, "rate_dps");
    row.line = line_number;
    const TextField& file_field = fields[index_of[3]];
    if (file_field.text.empty()) {
      throw Error(SourceLocation{listing_path, line_number, file_field.column}, "record listing: empty file name");
    }
    std::filesystem::path record_path{std::string(file_field.text)};
    if (record_path.is_relative()) record_path = directory / record_path;
    const std::string record = record_path.string();
    if (!std::filesystem::exists(record_path)) {
      throw Error(SourceLocation{listing_path, line_number, file_field.column},
                  fmt::format("record listing: record file '{}' does not exist", record));
    }
    const TextTable table = read_with_header(record);
    const RecordSource source{record, table.row_lines};
    const SourceLocation header{record, table.first_data_line > 0 ? table.first_data_line - 1 : 0, 0};
    RevolutionMean mean;
    if (table.has_column("table_angle_deg")) {
      mean = whole_revolution_mean_by_angle(table.column("table_angle_deg"), table.column("output"), source);
    } else if (table.has_column("time_s")) {
      mean = whole_revolution_mean_by_time(table.column("time_s"), table.column("output"), row.rate_dps, source);
    } else {
      throw Error(header,
                  "record: needs a 'table_angle_deg' or a 'time_s' column to cut whole revolutions");
    }
    row.output = mean.mean;
    if (pulse_counts) {
      if (!table.has_column("time_s")) {
        throw Error(header,
                    "record: pulses counted per sample interval need a 'time_s' column for their interval");
      }
      row.output *= with_file_context(record, [&] { return mean_sample_rate_hz(table.column("time_s")); });
    }
    rows.push_back(row);
  }
  if (index_of.empty()) throw Error(SourceLocation{listing_path, 0, 0}, "record listing: no header line");
  if (rows.empty()) throw Error(SourceLocation{listing_path, 0, 0}, "record listing: no records listed");
  return rows;
}

std::vector<AccelerometerMisalignmentRow> read_accelerometer_misalignment_positions(const std::string& path) {
  const TextTable table = read_with_header(path);
  const auto& beta = table.column("beta_deg");
  const auto& output = table.column("output");
  const std::vector<double>* run = table.has_column("run") ? &table.column("run") : nullptr;
  std::vector<AccelerometerMisalignmentRow> rows(table.rows());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::size_t line = table.row_lines.empty() ? 0 : table.row_lines[i];
    long run_number = 1;
    if (run != nullptr) {
      const double value = (*run)[i];
      if (value != std::floor(value) || std::abs(value) > 1e15) {
        throw Error(SourceLocation{path, line, 0}, fmt::format("run '{}' is not an integer", value));
      }
      run_number = static_cast<long>(value);
    }
    rows[i] = {beta[i], output[i], run_number, line};
  }
  return rows;
}

}  // namespace inertest

#include "inertest/io/rate_record.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "inertest/core/error.h"
#include "io/text_rows.h"

namespace inertest {
namespace {

constexpr std::size_t kChunkBytes = 4u << 20;
static_assert(std::endian::native == std::endian::little, "raw f64/f32 records are little-endian");

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File open(const std::string& path) {
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) throw Error(SourceLocation{path, 0, 0}, std::string("cannot open: ") + std::strerror(errno));
  return file;
}

std::size_t read_binary(const RateRecordSource& source, const SampleSink& sink) {
  const std::size_t sample_size = source.format == RateRecordFormat::kFloat64 ? 8 : 4;
  File file = open(source.path);
  std::vector<char> bytes(kChunkBytes);
  std::vector<double> samples(kChunkBytes / sample_size);
  std::size_t count = 0;
  std::size_t carried = 0;  // bytes of an incomplete sample kept from the last read
  while (true) {
    const std::size_t got = std::fread(bytes.data() + carried, 1, bytes.size() - carried, file.get());
    if (got == 0) {
      if (std::ferror(file.get())) throw Error(SourceLocation{source.path, 0, 0}, "read error");
      break;
    }
    const std::size_t available = carried + got;
    const std::size_t whole = available / sample_size;
    for (std::size_t i = 0; i < whole; ++i) {
      double value = 0.0;
      if (sample_size == 8) {
        std::memcpy(&value, bytes.data() + i * 8, 8);
      } else {
        float narrow = 0.0F;
        std::memcpy(&narrow, bytes.data() + i * 4, 4);
        value = static_cast<double>(narrow);
      }
      if (!std::isfinite(value)) {
        throw Error(SourceLocation{source.path, 0, 0},
                    "sample " + std::to_string(count + i + 1) + " is not a finite number");
      }
      samples[i] = value;
    }
    count += whole;
    if (whole > 0) sink(std::span<const double>(samples.data(), whole));
    carried = available - whole * sample_size;
    std::memmove(bytes.data(), bytes.data() + whole * sample_size, carried);
  }
  if (carried != 0) {
    throw Error(SourceLocation{source.path, 0, 0},
                "the size is not a whole number of " + std::to_string(sample_size) + "-byte samples (" +
                    std::to_string(carried) + " trailing bytes)");
  }
  if (count == 0) throw Error(SourceLocation{source.path, 0, 0}, "no data: the file is empty");
  return count;
}

// Text records: read in buffers of whole lines, each parsed by the same row parser as
// read_text_table (text_rows.h), so that a bad cell gets the same message in every command.
std::size_t read_text(const RateRecordSource& source, const SampleSink& sink) {
  TextTableOptions options;
  options.record_row_lines = false;
  if (source.column) options.columns = {*source.column};
  File file = open(source.path);
  std::vector<char> buffer(kChunkBytes);
  std::optional<io_detail::RowLayout> layout;
  std::size_t lines_before = 0;  // lines in the buffers already parsed
  std::size_t count = 0;
  std::size_t carried = 0;  // bytes of an unfinished line kept from the last read
  while (true) {
    if (carried == buffer.size()) buffer.resize(2 * buffer.size());  // a line longer than the buffer
    const std::size_t got = std::fread(buffer.data() + carried, 1, buffer.size() - carried, file.get());
    if (got == 0 && std::ferror(file.get())) throw Error(SourceLocation{source.path, 0, 0}, "read error");
    const std::string_view text(buffer.data(), carried + got);
    // The whole lines; at the end of the file, everything (a last line without '\n' included).
    const std::size_t last_newline = text.rfind('\n');
    const std::string_view lines =
        got == 0 ? text : text.substr(0, last_newline == std::string_view::npos ? 0 : last_newline + 1);
    std::size_t data_begin = 0;
    std::size_t first_line = lines_before + 1;
    if (!layout) {
      io_detail::LineCursor cursor(lines, lines_before);
      const std::optional<io_detail::Line> first = io_detail::next_content_line(cursor, options.comment);
      data_begin = lines.size();
      if (first) {
        layout = io_detail::read_row_layout(*first, source.path, options);
        if (!source.column && layout->width != 1) {
          std::string names;
          for (const auto& name : layout->header_names) names += (names.empty() ? "" : ", ") + name;
          throw Error(SourceLocation{source.path, first->number, 1},
                      "the record has " + std::to_string(layout->width) + " columns" +
                          (layout->has_header ? " (" + names + ")" : "") +
                          ": choose one with --column (plan key `column`)");
        }
        data_begin = io_detail::first_data_offset(*layout, *first, cursor, lines);
        first_line = layout->first_data_line;
      }
    }
    if (layout && data_begin < lines.size()) {
      io_detail::RowChunk rows;
      io_detail::parse_rows(lines.substr(data_begin), first_line, *layout, rows);
      if (rows.error) std::rethrow_exception(rows.error);
      if (rows.row_count > 0) sink(rows.columns.front());
      count += rows.row_count;
    }
    if (got == 0) break;
    lines_before += static_cast<std::size_t>(std::count(lines.begin(), lines.end(), '\n'));
    carried = text.size() - lines.size();
    std::memmove(buffer.data(), buffer.data() + lines.size(), carried);
  }
  if (!layout) io_detail::fail_no_content(source.path);
  io_detail::require_rows(source.path, count, 1);
  return count;
}

}  // namespace

RateRecordFormat parse_rate_record_format(std::string_view text) {
  if (text == "csv") return RateRecordFormat::kCsv;
  if (text == "f64") return RateRecordFormat::kFloat64;
  if (text == "f32") return RateRecordFormat::kFloat32;
  throw Error("unknown record format '" + std::string(text) + "' (expected csv, f64 or f32)");
}

std::size_t read_rate_record(const RateRecordSource& source, const SampleSink& sink) {
  return source.format == RateRecordFormat::kCsv ? read_text(source, sink) : read_binary(source, sink);
}

}  // namespace inertest

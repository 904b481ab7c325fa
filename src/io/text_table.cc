#include "inertest/io/text_table.h"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <optional>
#include <thread>

#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/huge_pages.h"
#include "inertest/io/mapped_file.h"
#include "io/decimal.h"
#include "io/text_rows.h"

namespace inertest {
namespace {

using io_detail::Field;
using io_detail::Line;
using io_detail::LineCursor;
using io_detail::RowChunk;
using io_detail::RowLayout;

// TextTableOptions::threads, else INERTEST_THREADS, else one per core.
std::size_t thread_count(const TextTableOptions& options) {
  if (options.threads > 0) return options.threads;
  if (const char* text = std::getenv("INERTEST_THREADS"); text != nullptr && *text != '\0') {
    std::size_t count = 0;
    const auto result = std::from_chars(text, text + std::strlen(text), count);
    if (result.ec != std::errc() || *result.ptr != '\0' || count == 0) {
      throw Error("INERTEST_THREADS must be a positive integer, not '" + std::string(text) + "'");
    }
    return count;
  }
  return std::max(1U, std::thread::hardware_concurrency());
}

// Splits data into one chunk per thread (at line boundaries; small inputs stay whole) and parses
// them in parallel, each straight into its part of `columns` (one per layout position, sized here
// for every line, in parallel, and advised for huge pages); then closes the gaps left by lines that
// were not rows (blank, comment) and cuts the columns to the rows. Results are in file order.
std::vector<RowChunk> parse_chunks(std::string_view data, std::size_t first_line, const RowLayout& layout,
                                   const TextTableOptions& options, std::vector<std::vector<double>>& columns) {
  const std::size_t threads = std::clamp<std::size_t>(data.size() / std::max<std::size_t>(options.minimum_chunk_bytes, 1),
                                                      1, thread_count(options));
  std::vector<std::string_view> pieces;
  std::size_t begin = 0;
  for (std::size_t t = 1; t <= threads; ++t) {
    std::size_t end = t == threads ? data.size() : std::max(begin, t * data.size() / threads);
    if (end < data.size()) {
      const std::size_t newline = data.find('\n', end);
      end = newline == std::string_view::npos ? data.size() : newline + 1;
    }
    pieces.push_back(data.substr(begin, end - begin));
    begin = end;
  }
  // Each chunk's first line number and first slot: the lines of the chunks before it, counted in
  // parallel too (the count is the first touch of the mapped file).
  const auto in_parallel = [&](auto&& work) {
    std::vector<std::thread> workers;
    for (std::size_t i = 1; i < pieces.size(); ++i) workers.emplace_back(work, i);
    work(0);
    for (auto& worker : workers) worker.join();
  };
  std::vector<std::size_t> line_counts(pieces.size());
  in_parallel([&](std::size_t i) { line_counts[i] = io_detail::line_capacity(pieces[i]); });
  std::vector<std::size_t> first_lines(pieces.size(), first_line);
  std::vector<std::size_t> first_slots(pieces.size() + 1, 0);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    // line_capacity counts a last line without '\n'; every chunk but the last ends with one, so
    // its rows fill exactly its '\n' count of slots, and the next chunk's rows follow with no gap
    // to close (moving the rest of every column by one slot was a serial copy of the record).
    const std::size_t lines = line_counts[i] - (pieces[i].ends_with('\n') ? 1 : 0);
    first_slots[i + 1] = first_slots[i] + lines;
    if (i + 1 < pieces.size()) first_lines[i + 1] = first_lines[i] + lines;
  }
  // The columns sized side by side, a column to a thread: the zero fill is the first touch of their
  // pages (each fault a page the kernel clears), a tenth of the six-channel run's CPU time when the
  // main thread did it alone.
  columns.resize(layout.positions.size());
  in_parallel([&](std::size_t i) {
    for (std::size_t c = i; c < columns.size(); c += pieces.size()) resize_on_huge_pages(columns[c], first_slots.back());
  });
  std::vector<RowChunk> results(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (auto& column : columns) results[i].columns.push_back(column.data() + first_slots[i]);
  }
  in_parallel([&](std::size_t i) { io_detail::parse_rows(pieces[i], first_lines[i], layout, results[i]); });
  std::size_t rows = 0;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (first_slots[i] != rows) {
      for (auto& column : columns) {
        std::copy_n(column.begin() + static_cast<std::ptrdiff_t>(first_slots[i]), results[i].row_count,
                    column.begin() + static_cast<std::ptrdiff_t>(rows));
      }
    }
    rows += results[i].row_count;
  }
  for (auto& column : columns) column.resize(rows);
  return results;
}

// The options to read the first line with: as given, except that a first line of blank-separated
// fields over rows of one field is one column whose name holds blanks ("gyro_x (pulse/s)"), read
// whole (split, it named two columns and every row was short of one).
TextTableOptions single_column_header(const Line& first, const LineCursor& cursor, const TextTableOptions& options,
                                      const std::string& source) {
  if (options.delimiter != '\0' || first.text.find_first_of(",;\t") != std::string_view::npos) return options;
  std::vector<io_detail::Field> fields;
  io_detail::split(first.text, ' ', fields, source, first.number);
  if (fields.size() < 2) return options;
  LineCursor peek = cursor;
  const std::optional<Line> row = io_detail::next_content_line(peek, options.comment);
  if (!row) return options;
  io_detail::split(row->text, ' ', fields, source, row->number);
  if (fields.size() != 1) return options;
  const std::string_view only = fields.front().text;
  double value = 0.0;
  const auto parsed = io_detail::parse_decimal(only.data(), only.data() + only.size(), value);
  if (parsed.ec != std::errc() || parsed.ptr != only.data() + only.size()) return options;  // not one number
  TextTableOptions whole_line = options;
  whole_line.delimiter = ',';
  return whole_line;
}

// The first line that is neither blank nor a comment decides delimiter and header (after Excel's
// "sep=;" line, which names the delimiter): its layout, with `cursor` past it and `first` set to it. Throws Error for a text of no such line.
RowLayout first_line_layout(const std::string& source, const TextTableOptions& options, LineCursor& cursor,
                            std::optional<Line>& first) {
  first = io_detail::next_content_line(cursor, options.comment);
  if (!first) io_detail::fail_no_content(source);
  if (const char separator = io_detail::excel_separator(first->text); separator != '\0') {
    TextTableOptions named = options;
    if (named.delimiter == '\0') named.delimiter = separator;
    first = io_detail::next_content_line(cursor, options.comment);
    if (!first) io_detail::fail_no_content(source);
    return io_detail::read_row_layout(*first, source, named);
  }
  return io_detail::read_row_layout(*first, source, single_column_header(*first, cursor, options, source));
}

}  // namespace

TextTableHeader parse_text_table_header(std::string_view text, const std::string& source,
                                        const TextTableOptions& options) {
  text = without_byte_order_mark(text);
  LineCursor cursor(text);
  std::optional<Line> first;
  const RowLayout layout = first_line_layout(source, options, cursor, first);
  if (!layout.has_header) return {};
  return {layout.header_names, first->number};
}

ColumnSelector ColumnSelector::parse(std::string_view text) {
  ColumnSelector selector;
  std::size_t index = 0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), index);
  if (result.ec == std::errc() && result.ptr == text.data() + text.size()) {
    if (index == 0) throw Error("column numbers are 1-based; 0 is not a column");
    selector.index = index;
  } else {
    selector.name = std::string(text);
  }
  return selector;
}

std::string ColumnSelector::to_string() const {
  return index > 0 ? "column " + std::to_string(index) : "column '" + name + "'";
}

const std::vector<double>& TextTable::column(std::string_view name) const {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return columns[i];
  }
  std::string known;
  for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
  throw Error(SourceLocation{source, 0, 0}, "no column '" + std::string(name) + "' (columns: " + known + ")");
}

bool TextTable::has_column(std::string_view name) const {
  return std::find(names.begin(), names.end(), name) != names.end();
}

TextTable parse_text_table(std::string_view text, const std::string& source, const TextTableOptions& options) {
  // A UTF-8 byte order mark (Excel's "CSV UTF-8" and many loggers write one) is no part of the
  // first cell, and editors do not show it, so columns are counted after it.
  text = without_byte_order_mark(text);
  // Lines ended by CR alone (classic Mac OS) would read as one line of many fields. Looked for only
  // in a text without LF (the search for an LF ends at the first line of any other record).
  if (text.find('\n') == std::string_view::npos) {
    if (const std::size_t cr = text.find('\r'); cr != std::string_view::npos && cr + 1 < text.size()) {
      throw Error(SourceLocation{source, 1, cr + 1},
                  "the lines end in a carriage return alone (CR, classic Mac OS): inertest reads LF or CR LF line ends");
    }
  }
  TextTable table;
  table.source = source;
  LineCursor cursor(text);
  std::optional<Line> first;
  const RowLayout layout = first_line_layout(source, options, cursor, first);
  for (std::size_t p : layout.positions) table.names.push_back(layout.header_names[p]);
  table.delimiter = layout.delimiter;
  table.header_line = layout.has_header ? first->number : 0;
  table.fields = layout.positions;

  // The data rows: from the first data line (the header line excluded) to the end, cut into one
  // chunk per core at line boundaries and parsed in parallel. Line numbers stay exact: each chunk
  // starts at the line count of the chunks before it.
  const std::size_t data_begin = io_detail::first_data_offset(layout, *first, cursor, text);
  const std::vector<RowChunk> chunks =
      parse_chunks(text.substr(data_begin), layout.first_data_line, layout, options, table.columns);
  std::size_t row_count = 0;
  for (const auto& chunk : chunks) {
    if (chunk.error) std::rethrow_exception(chunk.error);
    row_count += chunk.row_count;
  }
  io_detail::require_rows(source, row_count, options.minimum_rows);
  for (const auto& chunk : chunks) {
    if (table.first_data_line == 0 && chunk.first_line != 0) table.first_data_line = chunk.first_line;
    table.row_lines.insert(table.row_lines.end(), chunk.row_lines.begin(), chunk.row_lines.end());
  }
  return table;
}

SourceLocation locate_cell(const TextTable& table, std::size_t row, std::size_t column) {
  SourceLocation location{table.source, row < table.row_lines.size() ? table.row_lines[row] : 0, 0};
  std::error_code error;
  if (location.line == 0 || column >= table.fields.size() || !std::filesystem::is_regular_file(table.source, error)) {
    return location;
  }
  const MappedFile file(table.source);
  LineCursor cursor(file.text());
  Line line{};
  while (cursor.next(line)) {
    if (line.number != location.line) continue;
    std::vector<Field> fields;
    io_detail::split(line.text, table.delimiter, fields, table.source, line.number);
    if (table.fields[column] < fields.size()) location.column = fields[table.fields[column]].column;
    break;
  }
  return location;
}

TextTable read_text_table(const std::string& path, const TextTableOptions& options) {
  const MappedFile file(path);
  try {
    return parse_text_table(file.bytes(), path, options);
  } catch (const Error& e) {
    // A binary record read as text fails at some cell; say what it is instead (text holds no NUL).
    const std::string_view head = file.bytes().substr(0, 4096);
    const std::size_t nul = head.find('\0');
    if (nul == std::string_view::npos) throw;
    throw Error(SourceLocation{path, 0, 0}, "not text: a NUL byte at offset " + std::to_string(nul) +
                                                 " (a binary record? give its format, e.g. --format f64, f32, i32 or i16)");
  }
}

void require_increasing_time(const TextTable& table, std::size_t column) {
  const std::vector<double>& time = table.columns.at(column);
  for (std::size_t i = 1; i < time.size(); ++i) {
    if (!(time[i] > time[i - 1])) {
      throw Error(locate_cell(table, i, column),
                  fmt::format("time {} s does not follow the previous time {} s: times must increase", time[i], time[i - 1]));
    }
  }
}

}  // namespace inertest

#include "inertest/io/text_table.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cctype>
#include <cstring>
#include <fast_float/fast_float.h>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <optional>
#include <thread>

#include "inertest/core/error.h"
#include "inertest/io/mapped_file.h"

namespace inertest {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

struct Line {
  std::string_view text;  // without '\n' and trailing '\r'
  std::size_t number;     // 1-based
};

// Iterates lines of a buffer with memchr.
class LineCursor {
 public:
  explicit LineCursor(std::string_view text, std::size_t lines_before = 0) : text_(text), number_(lines_before) {}
  // Offset of the next line's first byte.
  std::size_t position() const { return pos_; }
  bool next(Line& line) {
    if (pos_ >= text_.size()) return false;
    const char* begin = text_.data() + pos_;
    const void* found = std::memchr(begin, '\n', text_.size() - pos_);
    const std::size_t end = found ? static_cast<std::size_t>(static_cast<const char*>(found) - text_.data()) : text_.size();
    std::size_t stop = end;
    if (stop > pos_ && text_[stop - 1] == '\r') --stop;
    line = {text_.substr(pos_, stop - pos_), ++number_};
    pos_ = end + 1;
    return true;
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t number_ = 0;
};

bool is_skipped(std::string_view line, char comment) {
  std::size_t i = 0;
  while (i < line.size() && is_blank(line[i])) ++i;
  return i == line.size() || (comment != '\0' && line[i] == comment);
}

// A line holding both ',' and ';' is taken as ';'-separated with decimal commas, the common
// European lab export, so that the cells are reported as decimal commas rather than misread.
char detect_delimiter(std::string_view line) {
  for (char candidate : {'\t', ';', ','}) {
    if (line.find(candidate) != std::string_view::npos) return candidate;
  }
  return ' ';
}

// A field: its text trimmed of blanks, and its 1-based column in the line.
struct Field {
  std::string_view text;
  std::size_t column;
};

// Splits a line into fields. delimiter ' ' means runs of blanks.
void split(std::string_view line, char delimiter, std::vector<Field>& fields) {
  fields.clear();
  std::size_t i = 0;
  const std::size_t n = line.size();
  if (delimiter == ' ') {
    while (i < n) {
      while (i < n && is_blank(line[i])) ++i;
      if (i == n) break;
      const std::size_t start = i;
      while (i < n && !is_blank(line[i])) ++i;
      fields.push_back({line.substr(start, i - start), start + 1});
    }
    return;
  }
  for (;;) {
    std::size_t start = i;
    while (i < n && line[i] != delimiter) ++i;
    std::size_t stop = i;
    while (start < stop && is_blank(line[start])) ++start;
    while (stop > start && is_blank(line[stop - 1])) --stop;
    fields.push_back({line.substr(start, stop - start), start + 1});
    if (i == n) break;
    ++i;
  }
}

std::string printable(std::string_view text) {
  std::string out(text.substr(0, 40));
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20) c = '?';
  }
  return text.size() > 40 ? out + "..." : out;
}

// Parses one numeric cell; nullopt when the text is not exactly one finite number.
std::optional<double> parse_number(std::string_view text) {
  if (text.empty()) return std::nullopt;
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (*begin == '+') ++begin;  // fast_float rejects a leading '+'
  double value = 0.0;
  const auto result = fast_float::from_chars(begin, end, value);
  if (result.ec != std::errc() || result.ptr != end) return std::nullopt;
  return value;
}

// Decimal commas ("1,25" in a ';' or whitespace separated file) are a common lab export.
bool is_decimal_comma(std::string_view text) {
  return text.find(',') != std::string_view::npos &&
         std::any_of(text.begin(), text.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }) &&
         std::all_of(text.begin(), text.end(), [](char c) {
           return std::isdigit(static_cast<unsigned char>(c)) || c == ',' || c == '-' || c == '+';
         });
}

[[noreturn]] void fail_decimal_comma(const SourceLocation& location, std::string_view text, const std::string& where) {
  throw Error(location, "'" + printable(text) + "'" + where + " looks like a decimal comma; inertest expects a decimal point");
}

[[noreturn]] void fail_cell(const std::string& source, const Line& line, const Field& field,
                            const std::string& column_name) {
  const std::string where = column_name.empty() ? "" : " in column '" + column_name + "'";
  const SourceLocation location{source, line.number, field.column};
  if (field.text.empty()) throw Error(location, "empty cell" + where + ", expected a number");
  if (is_decimal_comma(field.text)) fail_decimal_comma(location, field.text, where);
  throw Error(location, "expected a number" + where + ", found '" + printable(field.text) + "'");
}

// What every data row must look like, decided from the first line.
struct RowLayout {
  const std::string& source;
  char delimiter;
  std::size_t width;
  bool has_header;
  const std::vector<std::size_t>& positions;
  const std::vector<std::string>& header_names;
  const TextTableOptions& options;
};

bool is_header_again(const RowLayout& layout, const std::vector<Field>& fields) {
  if (!layout.has_header || fields.size() != layout.header_names.size()) return false;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (fields[i].text != layout.header_names[i]) return false;
  }
  return true;
}

// A row with the wrong number of fields. The column is where the first missing field would start
// (the line's end) or where the first extra field starts.
[[noreturn]] void fail_width(const RowLayout& layout, const Line& row, const std::vector<Field>& fields,
                             std::string_view chunk) {
  const bool too_few = fields.size() < layout.width;
  std::size_t column = too_few ? row.text.size() + 1 : fields[layout.width].column;
  std::string hint;
  const bool unterminated = row.text.data() + row.text.size() == chunk.data() + chunk.size();
  if (too_few && unterminated) {
    hint = " (the last line has no line end: a truncated record?)";
  } else if (fields.size() == 1 && layout.width > 1) {
    for (char other : {',', ';', '\t'}) {
      if (other != layout.delimiter && row.text.find(other) != std::string_view::npos) {
        column = row.text.find(other) + 1;
        hint = std::string(" (this line is separated by '") + (other == '\t' ? "\\t" : std::string(1, other)) +
               "', the record by '" + (layout.delimiter == '\t' ? "\\t" : std::string(1, layout.delimiter)) +
               "': mixed delimiters)";
        break;
      }
    }
  } else if (layout.has_header) {
    hint = " (a stray header or a truncated line?)";
  }
  throw Error(SourceLocation{layout.source, row.number, column},
              "expected " + std::to_string(layout.width) + " columns, found " + std::to_string(fields.size()) + hint);
}

struct ChunkResult {
  std::vector<std::vector<double>> columns;
  std::vector<std::size_t> row_lines;
  std::size_t row_count = 0;
  std::size_t first_line = 0;
  std::exception_ptr error;  // the first error in this chunk
};

void parse_rows(std::string_view chunk, std::size_t first_line, const RowLayout& layout, ChunkResult& result) {
  result.columns.resize(layout.positions.size());
  const std::size_t estimate = static_cast<std::size_t>(std::count(chunk.begin(), chunk.end(), '\n')) + 1;
  for (auto& c : result.columns) c.reserve(estimate);
  if (layout.options.record_row_lines) result.row_lines.reserve(estimate);
  LineCursor cursor(chunk, first_line - 1);
  Line row{};
  std::vector<Field> fields;
  try {
    while (cursor.next(row)) {
      if (is_skipped(row.text, layout.options.comment)) continue;
      split(row.text, layout.delimiter, fields);
      if (fields.size() != layout.width) fail_width(layout, row, fields, chunk);
      for (std::size_t k = 0; k < layout.positions.size(); ++k) {
        const Field& field = fields[layout.positions[k]];
        const auto value = parse_number(field.text);
        if (!value) {
          if (is_header_again(layout, fields)) {
            throw Error(SourceLocation{layout.source, row.number, 1},
                        "a second header row in the data (records joined together?)");
          }
          fail_cell(layout.source, row, field, layout.header_names[layout.positions[k]]);
        }
        if (!std::isfinite(*value)) {
          throw Error(SourceLocation{layout.source, row.number, field.column},
                      "'" + printable(field.text) + "' is not a finite number (NaN and Inf are not accepted)");
        }
        result.columns[k].push_back(*value);
      }
      if (layout.options.record_row_lines) result.row_lines.push_back(row.number);
      if (result.row_count++ == 0) result.first_line = row.number;
    }
  } catch (...) {
    result.error = std::current_exception();
  }
}

// Splits data into one chunk per core (at line boundaries; small inputs stay whole) and parses them
// in parallel; results are in file order.
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

std::vector<ChunkResult> parse_chunks(std::string_view data, std::size_t first_line, const RowLayout& layout) {
  const std::size_t threads = std::clamp<std::size_t>(data.size() / std::max<std::size_t>(layout.options.minimum_chunk_bytes, 1),
                                                      1, thread_count(layout.options));
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
  // Each chunk's first line number: lines counted in the chunks before it.
  std::vector<std::size_t> first_lines(pieces.size(), first_line);
  for (std::size_t i = 1; i < pieces.size(); ++i) {
    first_lines[i] = first_lines[i - 1] + static_cast<std::size_t>(std::count(pieces[i - 1].begin(), pieces[i - 1].end(), '\n'));
  }
  std::vector<ChunkResult> results(pieces.size());
  std::vector<std::thread> workers;
  for (std::size_t i = 1; i < pieces.size(); ++i) {
    workers.emplace_back(parse_rows, pieces[i], first_lines[i], std::cref(layout), std::ref(results[i]));
  }
  parse_rows(pieces[0], first_lines[0], layout, results[0]);
  for (auto& worker : workers) worker.join();
  return results;
}

}  // namespace

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
  TextTable table;
  table.source = source;
  LineCursor cursor(text);
  Line line{};
  std::vector<Field> fields;

  // The first line that is neither blank nor a comment decides delimiter and header.
  bool found = false;
  while (cursor.next(line)) {
    if (!is_skipped(line.text, options.comment)) {
      found = true;
      break;
    }
  }
  if (!found) throw Error(SourceLocation{source, 0, 0}, "no data: the file is empty or holds only comments");
  if (line.text.find('\0') != std::string_view::npos) {
    throw Error(SourceLocation{source, line.number, line.text.find('\0') + 1},
                "binary data in a text record (use a binary format option)");
  }

  const char delimiter = options.delimiter != '\0' ? options.delimiter : detect_delimiter(line.text);
  split(line.text, delimiter, fields);
  const std::size_t width = fields.size();

  bool has_header = options.header == TextTableOptions::Header::kPresent;
  if (options.header == TextTableOptions::Header::kDetect) {
    has_header = std::any_of(fields.begin(), fields.end(), [](const Field& f) { return !parse_number(f.text); });
  }
  std::vector<std::string> header_names(width);
  if (has_header && options.header == TextTableOptions::Header::kDetect) {
    for (const Field& field : fields) {
      if (is_decimal_comma(field.text)) fail_decimal_comma(SourceLocation{source, line.number, field.column}, field.text, "");
    }
  }
  if (has_header) {
    for (std::size_t i = 0; i < width; ++i) header_names[i] = std::string(fields[i].text);
  }

  // Resolve the selected columns to 0-based positions.
  std::vector<std::size_t> positions;
  if (options.columns.empty()) {
    for (std::size_t i = 0; i < width; ++i) positions.push_back(i);
  } else {
    for (const auto& selector : options.columns) {
      if (selector.index > 0) {
        if (selector.index > width) {
          throw Error(SourceLocation{source, line.number, 1},
                      "column " + std::to_string(selector.index) + " asked for, but the record has " +
                          std::to_string(width) + " columns");
        }
        positions.push_back(selector.index - 1);
        continue;
      }
      if (!has_header) {
        throw Error(SourceLocation{source, line.number, 1},
                    "column '" + selector.name + "' asked for by name, but the record has no header row");
      }
      const auto it = std::find(header_names.begin(), header_names.end(), selector.name);
      if (it == header_names.end()) {
        std::string known;
        for (const auto& n : header_names) known += (known.empty() ? "" : ", ") + n;
        throw Error(SourceLocation{source, line.number, 1},
                    "no column '" + selector.name + "' in the header (columns: " + known + ")");
      }
      positions.push_back(static_cast<std::size_t>(it - header_names.begin()));
    }
  }
  for (std::size_t p : positions) table.names.push_back(header_names[p]);
  table.delimiter = delimiter;
  table.header_line = has_header ? line.number : 0;
  table.fields = positions;

  // The data rows: from the first data line (the header line excluded) to the end, cut into one
  // chunk per core at line boundaries and parsed in parallel. Line numbers stay exact: each chunk
  // starts at the line count of the chunks before it.
  // A header on the last line without a line end leaves the cursor one past the end.
  const std::size_t data_begin =
      has_header ? std::min(cursor.position(), text.size()) : static_cast<std::size_t>(line.text.data() - text.data());
  const std::size_t data_line = has_header ? line.number + 1 : line.number;
  const std::string_view data = text.substr(data_begin);
  const RowLayout layout{source, delimiter, width, has_header, positions, header_names, options};
  std::vector<ChunkResult> chunks = parse_chunks(data, data_line, layout);

  std::size_t row_count = 0;
  for (const auto& chunk : chunks) {
    if (chunk.error) std::rethrow_exception(chunk.error);
    row_count += chunk.row_count;
  }
  if (row_count == 0 || row_count < options.minimum_rows) {
    throw Error(SourceLocation{source, 0, 0},
                "expected at least " + std::to_string(std::max<std::size_t>(options.minimum_rows, 1)) +
                    " data rows, found " + std::to_string(row_count));
  }
  table.columns.resize(positions.size());
  for (std::size_t k = 0; k < positions.size(); ++k) {
    if (chunks.size() == 1) {
      table.columns[k] = std::move(chunks.front().columns[k]);
      continue;
    }
    table.columns[k].reserve(row_count);
    for (const auto& chunk : chunks) {
      table.columns[k].insert(table.columns[k].end(), chunk.columns[k].begin(), chunk.columns[k].end());
    }
  }
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
  LineCursor cursor(file.bytes());
  Line line{};
  while (cursor.next(line)) {
    if (line.number != location.line) continue;
    std::vector<Field> fields;
    split(line.text, table.delimiter, fields);
    if (table.fields[column] < fields.size()) location.column = fields[table.fields[column]].column;
    break;
  }
  return location;
}

TextTable read_text_table(const std::string& path, const TextTableOptions& options) {
  const MappedFile file(path);
  return parse_text_table(file.bytes(), path, options);
}

}  // namespace inertest

// The row parser behind every text record reader: the layout the first line fixes (delimiter,
// header, chosen columns) and the parse of a run of whole lines against it, RFC 4180 quoted fields
// included, with the messages of the bad-input corpus (file:line:column, decimal commas, mixed
// delimiters, a second header, NaN/Inf, a truncated last line, a quote left open or misplaced).
// parse_text_table (text_table.cc) runs it on chunks in parallel; every text reader goes through
// it. Private to io.
#pragma once

#include <cstddef>
#include <cstring>
#include <exception>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "inertest/io/text_table.h"

namespace inertest::io_detail {

struct Line {
  std::string_view text;  // without '\n' and trailing '\r'
  std::size_t number;     // 1-based
};

// Iterates lines of a buffer with memchr.
class LineCursor {
 public:
  explicit LineCursor(std::string_view text, std::size_t lines_before = 0) : text_(text), number_(lines_before) {}
  // Offset of the next line's first byte (one past the end after a last line without '\n').
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

// The next line that is neither blank nor a comment, or nullopt at the end of the buffer.
std::optional<Line> next_content_line(LineCursor& cursor, char comment);

// A field: its text trimmed of blanks (of a quoted field, the text between the quotes, a doubled
// quote still doubled), and its 1-based column in the line (of a quoted field, its opening quote).
struct Field {
  std::string_view text;
  std::size_t column;
  bool quoted = false;
  bool escaped = false;  // a quoted field holding a doubled quote: value() undoubles it
  // The field's value: text, with each doubled quote "" of a quoted field made one ".
  std::string value() const;
};

// The delimiter Excel's first line "sep=;" names for the lines after it (any one character, a tab
// included), or '\0' for any other line.
char excel_separator(std::string_view line);

// Splits a line into fields. delimiter ' ' means runs of blanks. A field may be quoted as RFC 4180
// says: "a,b" holds the delimiter, "" is a quote; blanks around the quotes are ignored. Throws Error
// at `source`:`line_number` (the column is the quote's) for a quote that does not close on its
// line or text after a closing quote. A quote inside an unquoted field is left in the field's text: a
// number cannot hold one (fail_cell names it) and a header name is checked by read_row_layout.
void split(std::string_view line, char delimiter, std::vector<Field>& fields, const std::string& source,
           std::size_t line_number);

// What every data row must look like, decided from the first line.
struct RowLayout {
  std::string source;
  char delimiter = ',';
  std::size_t width = 0;
  bool has_header = false;
  std::vector<std::string> header_names;  // one per field, "" without a header
  std::vector<std::size_t> positions;     // 0-based fields to keep, in the order asked
  char comment = '#';
  bool record_row_lines = true;
  // The line after the header, or the first line itself when it is data.
  std::size_t first_data_line = 0;
};

// The layout from the first line that is neither blank nor a comment. Throws Error for binary
// data, a decimal comma in a header, or a selected column the line does not have.
RowLayout read_row_layout(const Line& first, const std::string& source, const TextTableOptions& options);

// Offset in `text` of the first data row: where `cursor` stands after the header line (clamped
// for a header without a line end), or the first line itself when it is data.
std::size_t first_data_offset(const RowLayout& layout, const Line& first, const LineCursor& cursor,
                              std::string_view text);

// The errors of a record without data, the same from every reader: no line but blanks and
// comments, or fewer than `minimum` data rows (at least 1).
[[noreturn]] void fail_no_content(const std::string& source);
void require_rows(const std::string& source, std::size_t rows, std::size_t minimum);

// Lines in a chunk of text: its '\n' plus a last line without one; no chunk holds more rows.
std::size_t line_capacity(std::string_view chunk);

struct RowChunk {
  // Where the chunk's rows go, one array per layout position, each with room for
  // line_capacity(chunk) values (the caller's: the chunks of a table write into its columns).
  std::vector<double*> columns;
  std::vector<std::size_t> row_lines;        // with RowLayout::record_row_lines
  std::size_t row_count = 0;
  std::size_t first_line = 0;                // line of the first data row, 0 if none
  std::exception_ptr error;                  // the first error in the chunk; parsing stops there
};

// Which value slot each field of a row fills on the plain path, or empty when the plain path
// cannot serve the layout (a field asked for twice, a delimiter a number may hold). A field that
// fills none holds -r: it and the r - 1 after it are not selected (the plain path skips them as one
// run).
std::vector<int> plain_slots(const RowLayout& layout);

// The plain path of a data row: unquoted fields, each selected one exactly one finite number, the
// row as wide as the layout. It reads from `p` to the row's '\n' (or the chunk's end) once, with no
// line search and no field list, puts the numbers in values[slots[field]] and returns where it
// stopped. It accepts exactly the rows that the general path (split, then parse_number) accepts,
// with the same values, and declines (nullptr) every other, blank and comment lines included: the
// general path then reads that line again to skip it or to name its error.
const char* parse_plain_row(const char* p, const char* end, const RowLayout& layout, const std::vector<int>& slots,
                            double* values);

// Parses whole lines (a last line without '\n' is taken as the record's truncated end) starting at
// line number first_line, into result.columns. Never throws: an error is left in result.error.
void parse_rows(std::string_view chunk, std::size_t first_line, const RowLayout& layout, RowChunk& result);

}  // namespace inertest::io_detail

// Reading numeric columns from lab records in text form: CSV, TSV, semicolon or whitespace
// separated; with a header row or without; with comment lines. The file is memory-mapped and
// parsed with fast_float; no iostreams. Every problem is an Error naming file, line and column.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "inertest/core/error.h"

namespace inertest {

// A column chosen by its header name or by its 1-based position.
struct ColumnSelector {
  std::string name;       // used when index == 0
  std::size_t index = 0;  // 1-based; 0 means "by name"

  // "3" selects the third column; anything else selects by name.
  static ColumnSelector parse(std::string_view text);
  std::string to_string() const;
};

struct TextTableOptions {
  enum class Header { kDetect, kPresent, kAbsent };
  // '\0' detects the delimiter from the first data line: ',', '\t', ';', else whitespace runs.
  char delimiter = '\0';
  Header header = Header::kDetect;
  // Lines whose first non-blank character is this are skipped, as are blank lines.
  char comment = '#';
  // Columns to return, in this order; empty returns every column.
  std::vector<ColumnSelector> columns;
  // Minimum number of data rows; fewer is an Error.
  std::size_t minimum_rows = 1;
  // Keep the line number of every row (TextTable::row_lines). Off for records of 10^8+ samples.
  bool record_row_lines = true;
  // Threads parsing the data rows: 0 takes the INERTEST_THREADS environment variable when set,
  // else one per core. The result is the same whatever the count (same values, same errors).
  std::size_t threads = 0;
  // A thread is given a chunk only when each chunk holds at least this many bytes.
  std::size_t minimum_chunk_bytes = std::size_t{4} << 20;
};

struct TextTable {
  std::string source;                       // file name, for messages
  std::vector<std::string> names;           // header names of the returned columns ("" without header)
  std::vector<std::vector<double>> columns; // column-major values
  std::size_t first_data_line = 0;          // 1-based line of the first data row
  std::size_t header_line = 0;              // 1-based line of the header row (0: no header)
  // 1-based line of each data row, so procedures can point at the offending row (empty unless
  // TextTableOptions::record_row_lines).
  std::vector<std::size_t> row_lines;
  char delimiter = ',';                     // the delimiter used (' ' for runs of blanks)
  std::vector<std::size_t> fields;          // 0-based field of each returned column within a line

  std::size_t rows() const { return columns.empty() ? 0 : columns.front().size(); }
  // The returned column of that header name; throws Error listing the names present.
  const std::vector<double>& column(std::string_view name) const;
  bool has_column(std::string_view name) const;
};

TextTable read_text_table(const std::string& path, const TextTableOptions& options = {});

// The same, on text already in memory; `source` names it in messages.
TextTable parse_text_table(std::string_view text, const std::string& source, const TextTableOptions& options = {});

// The names of a text table's header, read as parse_text_table reads them, and its line; no names
// (line 0) when the first line is data. The data rows are not read.
struct TextTableHeader {
  std::vector<std::string> names;
  std::size_t line = 0;
};
TextTableHeader parse_text_table_header(std::string_view text, const std::string& source,
                                        const TextTableOptions& options = {});

// One field of a line of delimited text: its value (RFC 4180 quotes removed, a doubled "" made one
// ") and the 1-based column where it starts in the line.
struct TextField {
  std::string text;
  std::size_t column = 0;
};

// Splits one line of delimited text as the record readers do (delimiter ' ': runs of blanks; blanks
// around a field trimmed; RFC 4180 quotes), for files of text cells such as record listings.
// Throws Error at `source`:`line_number` with the column of a quote that does not close on its
// line, text after a closing quote, or a quote inside an unquoted field.
std::vector<TextField> split_text_line(std::string_view line, char delimiter, const std::string& source,
                                       std::size_t line_number);

// The lines of a file of text cells (a record listing, power supply readings) that are neither blank
// nor a '#' comment, each split as split_text_line splits it, at the delimiter the first of them
// shows (',', tab or ';', else runs of blanks), so that a listing saved by a European Excel (';')
// reads as one with commas. `line`: the 1-based line of the row.
struct TextCellRow {
  std::size_t line = 0;
  std::vector<TextField> cells;
};
std::vector<TextCellRow> split_text_cells(std::string_view text, const std::string& source);

// Where the cell of data row `row` (0-based) in returned column `column` is: file, line and
// character column, for errors found after reading (a time stamp going backwards, a stuck
// channel). Reads the line again from table.source when that is a file; the column is 0 when it
// is not, and the line is 0 without TextTable::row_lines.
SourceLocation locate_cell(const TextTable& table, std::size_t row, std::size_t column);

// Throws Error at the first cell of returned column `column`, the time of each row in s, that is
// not above the one before it (a logger's clock set back, a record pasted twice).
void require_increasing_time(const TextTable& table, std::size_t column);

}  // namespace inertest

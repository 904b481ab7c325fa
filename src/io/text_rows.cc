#include "io/text_rows.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "inertest/core/error.h"
#include "inertest/io/mapped_file.h"
#include "io/decimal.h"

namespace inertest::io_detail {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// Excel's error values: a cell that starts with one is a missing number, not the start of a '#'
// comment (a row "#N/A,20" dropped as a comment would shift every later sample in time).
bool is_spreadsheet_error(std::string_view text) {
  for (std::string_view error : {"#N/A", "#VALUE!", "#DIV/0!", "#REF!", "#NAME?", "#NUM!", "#NULL!"}) {
    if (text.starts_with(error)) return true;
  }
  return false;
}

bool is_skipped(std::string_view line, char comment) {
  std::size_t i = 0;
  while (i < line.size() && is_blank(line[i])) ++i;
  return i == line.size() || (comment != '\0' && line[i] == comment && !is_spreadsheet_error(line.substr(i)));
}

// A line holding both ',' and ';' is taken as ';'-separated with decimal commas, the common
// European lab export, so that the cells are reported as decimal commas rather than misread.
// Delimiters inside quoted fields ("time, s") do not count.
char detect_delimiter(std::string_view line) {
  bool quoted = false;
  bool found[3] = {false, false, false};
  constexpr char kCandidates[3] = {'\t', ';', ','};
  for (char c : line) {
    if (c == '"') quoted = !quoted;  // a doubled "" toggles twice
    for (std::size_t k = 0; k < 3; ++k) found[k] = found[k] || (!quoted && c == kCandidates[k]);
  }
  for (std::size_t k = 0; k < 3; ++k) {
    if (found[k]) return kCandidates[k];
  }
  return ' ';
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
  // fast_float rejects a leading '+': one is skipped, unless a sign follows ("+-1" is no number)
  if (*begin == '+' && !(end - begin > 1 && (begin[1] == '-' || begin[1] == '+'))) ++begin;
  double value = 0.0;
  const auto result = parse_decimal(begin, end, value);
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

// RFC 4180 2.5: a field holding a quote must be quoted as a whole, the quote doubled.
void check_no_stray_quote(const std::string& source, std::size_t line_number, const Field& field) {
  const std::size_t quote = field.quoted ? std::string_view::npos : field.text.find('"');
  if (quote != std::string_view::npos) {
    throw Error(SourceLocation{source, line_number, field.column + quote},
                "a quote inside an unquoted field '" + printable(field.text) +
                    "' (quote the whole field, as in \"a\"\"b\", or remove the quote)");
  }
}

[[noreturn]] void fail_cell(const std::string& source, const Line& line, const Field& field,
                            const std::string& column_name) {
  const std::string where = column_name.empty() ? "" : " in column '" + column_name + "'";
  const SourceLocation location{source, line.number, field.column};
  check_no_stray_quote(source, line.number, field);
  if (field.text.empty()) throw Error(location, "empty cell" + where + ", expected a number");
  if (is_decimal_comma(field.text)) fail_decimal_comma(location, field.text, where);
  throw Error(location, "expected a number" + where + ", found '" + printable(field.text) + "'");
}

bool is_header_again(const RowLayout& layout, const std::vector<Field>& fields) {
  if (!layout.has_header || fields.size() != layout.header_names.size()) return false;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (fields[i].value() != layout.header_names[i]) return false;
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

// The quoted field whose opening quote is at `open` (RFC 4180 2.5-2.7: it runs to the next quote
// that is not doubled; blanks after it are ignored). Appends it and returns the index of the
// delimiter (or the line's end) after it.
std::size_t split_quoted(std::string_view line, std::size_t open, char delimiter, std::vector<Field>& fields,
                         const std::string& source, std::size_t line_number) {
  const std::size_t n = line.size();
  bool escaped = false;
  std::size_t close = open + 1;
  for (;;) {
    close = line.find('"', close);
    if (close == std::string_view::npos) {
      throw Error(SourceLocation{source, line_number, open + 1},
                  "a quoted field with no closing quote on its line (a quote inside a quoted field is written \"\")");
    }
    if (close + 1 >= n || line[close + 1] != '"') break;
    escaped = true;
    close += 2;
  }
  std::size_t i = close + 1;
  if (delimiter != ' ') {
    while (i < n && line[i] != delimiter && is_blank(line[i])) ++i;
  }
  if (i < n && (delimiter == ' ' ? !is_blank(line[i]) : line[i] != delimiter)) {
    throw Error(SourceLocation{source, line_number, i + 1},
                "text after the closing quote of a quoted field (a quote inside a quoted field is written \"\")");
  }
  fields.push_back({line.substr(open + 1, close - open - 1), open + 1, true, escaped});
  return i;
}

}  // namespace

std::optional<Line> next_content_line(LineCursor& cursor, char comment) {
  Line line{};
  while (cursor.next(line)) {
    if (!is_skipped(line.text, comment)) return line;
  }
  return std::nullopt;
}

char excel_separator(std::string_view line) {
  return line.size() == 5 && line.substr(0, 4) == "sep=" ? line[4] : '\0';
}

std::string Field::value() const {
  if (!escaped) return std::string(text);
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '"') ++i;  // the second quote of a doubled ""
  }
  return out;
}

// The unquoted paths are those of a record without quotes, kept as lean as they were: the
// quote costs one comparison per field.
void split(std::string_view line, char delimiter, std::vector<Field>& fields, const std::string& source,
           std::size_t line_number) {
  fields.clear();
  std::size_t i = 0;
  const std::size_t n = line.size();
  if (delimiter == ' ') {
    while (i < n) {
      while (i < n && is_blank(line[i])) ++i;
      if (i == n) break;
      const std::size_t start = i;
      if (line[start] == '"') {
        i = split_quoted(line, start, delimiter, fields, source, line_number);
        continue;
      }
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
    if (start < stop && line[start] == '"') {
      i = split_quoted(line, start, delimiter, fields, source, line_number);  // the field may hold delimiters
    } else {
      while (stop > start && is_blank(line[stop - 1])) --stop;
      fields.push_back({line.substr(start, stop - start), start + 1});
    }
    if (i == n) break;
    ++i;
  }
}

RowLayout read_row_layout(const Line& first, const std::string& source, const TextTableOptions& options) {
  if (first.text.find('\0') != std::string_view::npos) {
    throw Error(SourceLocation{source, first.number, first.text.find('\0') + 1},
                "binary data in a text record (use a binary format option)");
  }
  RowLayout layout;
  layout.source = source;
  layout.comment = options.comment;
  layout.record_row_lines = options.record_row_lines;
  layout.delimiter = options.delimiter != '\0' ? options.delimiter : detect_delimiter(first.text);
  std::vector<Field> fields;
  split(first.text, layout.delimiter, fields, source, first.number);
  layout.width = fields.size();

  layout.has_header = options.header == TextTableOptions::Header::kPresent;
  if (options.header == TextTableOptions::Header::kDetect) {
    // A header has a cell that is text; an empty cell is no text (a first data row with a missing
    // value is a data row, and its empty cell an error, as in any other row).
    layout.has_header = std::any_of(fields.begin(), fields.end(),
                                    [](const Field& f) { return !f.text.empty() && !parse_number(f.text); });
    for (const Field& field : fields) {
      if (layout.has_header && is_decimal_comma(field.text)) {
        fail_decimal_comma(SourceLocation{source, first.number, field.column}, field.text, "");
      }
    }
  }
  layout.header_names.resize(layout.width);
  if (layout.has_header) {
    for (std::size_t i = 0; i < layout.width; ++i) {
      check_no_stray_quote(source, first.number, fields[i]);
      layout.header_names[i] = fields[i].value();
    }
  }
  layout.first_data_line = layout.has_header ? first.number + 1 : first.number;

  // Resolve the selected columns to 0-based positions.
  if (options.columns.empty()) {
    for (std::size_t i = 0; i < layout.width; ++i) layout.positions.push_back(i);
    return layout;
  }
  for (const auto& selector : options.columns) {
    if (selector.index > 0) {
      if (selector.index > layout.width) {
        throw Error(SourceLocation{source, first.number, 1},
                    "column " + std::to_string(selector.index) + " asked for, but the record has " +
                        std::to_string(layout.width) + " columns");
      }
      layout.positions.push_back(selector.index - 1);
      continue;
    }
    if (!layout.has_header) {
      throw Error(SourceLocation{source, first.number, 1},
                  "column '" + selector.name + "' asked for by name, but the record has no header row");
    }
    const auto it = std::find(layout.header_names.begin(), layout.header_names.end(), selector.name);
    if (it == layout.header_names.end()) {
      std::string known;
      for (const auto& n : layout.header_names) known += (known.empty() ? "" : ", ") + n;
      // "rate (deg/h)" for "rate": the unit belongs in the command's unit option, not the name.
      std::string hint;
      for (const auto& n : layout.header_names) {
        if (!n.starts_with(selector.name)) continue;
        std::string_view rest = std::string_view(n).substr(selector.name.size());
        while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
        if (!rest.empty() && (rest.front() == '(' || rest.front() == '[')) {
          hint = fmt::format(": name the column '{}' and give the unit {} where the command takes one (e.g. "
                             "--rate-unit, rate_unit)",
                             selector.name, rest);
          break;
        }
      }
      throw Error(SourceLocation{source, first.number, 1},
                  "no column '" + selector.name + "' in the header (columns: " + known + ")" + hint);
    }
    // Two columns of one name (an export with two "output" columns): the first was taken silently.
    if (const auto again = std::find(it + 1, layout.header_names.end(), selector.name);
        again != layout.header_names.end()) {
      throw Error(SourceLocation{source, first.number, 1},
                  fmt::format("the header names columns {} and {} '{}': ask for one by its number",
                              it - layout.header_names.begin() + 1, again - layout.header_names.begin() + 1,
                              selector.name));
    }
    layout.positions.push_back(static_cast<std::size_t>(it - layout.header_names.begin()));
  }
  return layout;
}

std::size_t first_data_offset(const RowLayout& layout, const Line& first, const LineCursor& cursor,
                              std::string_view text) {
  return layout.has_header ? std::min(cursor.position(), text.size())
                           : static_cast<std::size_t>(first.text.data() - text.data());
}

void fail_no_content(const std::string& source) {
  throw Error(SourceLocation{source, 0, 0}, "no data: the file is empty or holds only comments");
}

void require_rows(const std::string& source, std::size_t rows, std::size_t minimum) {
  minimum = std::max<std::size_t>(minimum, 1);
  if (rows < minimum) {
    throw Error(SourceLocation{source, 0, 0},
                "expected at least " + std::to_string(minimum) + " data rows, found " + std::to_string(rows));
  }
}

std::vector<int> plain_slots(const RowLayout& layout) {
  // The plain path reads a number up to the first byte that cannot continue it and takes that byte
  // for the delimiter: a delimiter a number may hold ("1.5" split at '.') is left to split(), and
  // so is '\r', which the general path drops from a CRLF line's end before it splits the line.
  const unsigned char delimiter = static_cast<unsigned char>(layout.delimiter);
  if (std::isalnum(delimiter) || std::string_view(".+-\r").find(layout.delimiter) != std::string_view::npos) return {};
  std::vector<int> slots(layout.width, -1);
  for (std::size_t k = 0; k < layout.positions.size(); ++k) {
    int& slot = slots[layout.positions[k]];
    if (slot >= 0) return {};
    slot = static_cast<int>(k);
  }
  for (std::size_t field = layout.width; field-- > 1;) {
    if (slots[field] < 0 && slots[field - 1] < 0) slots[field - 1] = slots[field] - 1;
  }
  return slots;
}

namespace {

constexpr std::uint64_t kOnes = 0x0101010101010101ULL;

// 0x80 in each byte of x that is zero, 0 in every other: the exact SWAR test of Hacker's Delight,
// 2nd ed., 6-1 (no carry from one byte reaches the next).
std::uint64_t zero_bytes(std::uint64_t x) {
  constexpr std::uint64_t kLow7 = 0x7f7f7f7f7f7f7f7fULL;
  return ~(((x & kLow7) + kLow7) | x | kLow7);
}

// The end of an unselected field of the plain path: the first byte from p on that is a line end, a
// quote or the field's end (the delimiter; with delimiter ' ', a blank), or `end`. Eight bytes a step
// while eight remain: the bytes equal to each stop marked by zero_bytes, the lowest mark first.
template <bool kBlankSeparated>
const char* skip_field(const char* p, const char* end, char delimiter) {
  const auto marks = [](std::uint64_t word, unsigned char stop) { return zero_bytes(word ^ (kOnes * stop)); };
  for (; end - p >= 8; p += 8) {
    const std::uint64_t word = load_eight_bytes(p);
    std::uint64_t stops = marks(word, '\n') | marks(word, '"');
    if constexpr (kBlankSeparated) {
      stops |= marks(word, ' ') | marks(word, '\t') | marks(word, '\r');
    } else {
      stops |= marks(word, static_cast<unsigned char>(delimiter));
    }
    if (stops != 0) return p + std::countr_zero(stops) / 8;
  }
  while (p < end && *p != '\n' && *p != '"' && (kBlankSeparated ? !is_blank(*p) : *p != delimiter)) ++p;
  return p;
}

// The end of `count` unselected fields of a delimited row from p: the stop (the delimiter, a line
// end, a quote, or `end`) that ends the last of them, or nullptr where one before it is not the
// delimiter. With SSE2 (every x86-64), sixty-four bytes a step: their stops are the bits of a mask,
// taken in order, so that a field costs no load that waits on the one before (one column of 2e6
// seven-column rows: 107 -> 58 ms on one thread); the rest, and other machines, a field at a time.
const char* skip_fields(const char* p, const char* end, std::size_t count, char delimiter) {
#if defined(__SSE2__)
  const __m128i delimiters = _mm_set1_epi8(delimiter);
  const __m128i line_ends = _mm_set1_epi8('\n');
  const __m128i quotes = _mm_set1_epi8('"');
  const auto stop_bits = [&](const char* q) {
    const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(q));
    const __m128i stops = _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi8(bytes, delimiters), _mm_cmpeq_epi8(bytes, line_ends)),
                                       _mm_cmpeq_epi8(bytes, quotes));
    return static_cast<std::uint64_t>(static_cast<unsigned>(_mm_movemask_epi8(stops)));
  };
  for (; end - p >= 64; p += 64) {
    std::uint64_t stops = stop_bits(p) | stop_bits(p + 16) << 16 | stop_bits(p + 32) << 32 | stop_bits(p + 48) << 48;
    for (; stops != 0; stops &= stops - 1) {
      const char* stop = p + std::countr_zero(stops);
      if (--count == 0) return stop;
      if (*stop != delimiter) return nullptr;
    }
  }
#endif
  for (;;) {
    p = skip_field<false>(p, end, delimiter);
    if (--count == 0) return p;
    if (p == end || *p != delimiter) return nullptr;
    ++p;
  }
}

}  // namespace

const char* parse_plain_row(const char* p, const char* end, const RowLayout& layout, const std::vector<int>& slots,
                            double* values) {
  const char delimiter = layout.delimiter;
  const bool blank_separated = delimiter == ' ';
  // The blanks around a field; a tab delimiter is none of them (a tab-separated row, LabVIEW's
  // export, went the general way when this skipped its delimiters).
  const auto is_padding = [&](char c) { return is_blank(c) && (blank_separated || c != delimiter); };
  for (std::size_t field = 0; field < layout.width; ++field) {
    while (p < end && is_padding(*p)) ++p;
    if (p < end && *p == '"') return nullptr;
    // A comment line (or an Excel error, which is_skipped tells apart), after blanks as is_skipped
    // counts them (a tab delimiter too): the general path's. The first field is not always a number
    // that would decline it: "# pause,5" with column 2 selected.
    if (field == 0 && layout.comment != '\0') {
      const char* q = p;
      while (q < end && is_blank(*q)) ++q;
      if (q < end && *q == layout.comment) return nullptr;
    }
    if (slots[field] >= 0) {
      // as parse_number: a leading '+' skipped unless a sign follows
      if (p < end && *p == '+' && !(end - p > 1 && (p[1] == '-' || p[1] == '+'))) ++p;
      double value = 0.0;
      const auto parsed = parse_decimal(p, end, value);
      if (parsed.ec != std::errc() || !std::isfinite(value)) return nullptr;
      p = parsed.ptr;
      values[slots[field]] = value;
    } else if (blank_separated) {
      p = skip_field<true>(p, end, delimiter);
      if (p < end && *p == '"') return nullptr;
    } else {
      const auto run = static_cast<std::size_t>(-slots[field]);  // this field and those after it up to a selected one
      p = skip_fields(p, end, run, delimiter);
      if (p == nullptr || (p < end && *p == '"')) return nullptr;
      field += run - 1;
    }
    const bool last = field + 1 == layout.width;
    if (blank_separated) {
      if (p < end && *p != '\n' && !is_blank(*p)) return nullptr;  // text after the number
      while (p < end && is_blank(*p)) ++p;
      const bool line_ends = p == end || *p == '\n';
      if (last != line_ends) return nullptr;  // too few or too many fields
    } else {
      while (p < end && is_padding(*p)) ++p;
      if (last) return p == end || *p == '\n' ? p : nullptr;
      if (p == end || *p != delimiter) return nullptr;
      ++p;
    }
  }
  return p;
}

std::size_t line_capacity(std::string_view chunk) {
  std::size_t count = 0;
  std::size_t i = 0;
#if defined(__SSE2__)
  // Sixteen bytes a step: each '\n' is 0xFF in the comparison, subtracted (+1) from its lane's byte
  // counter; every 255 steps, before a counter could wrap, the counters are summed (psadbw). The
  // 8-byte word form below took a quarter of the row parser's time on the bench record (116 MB,
  // 5e6 rows of two numbers: 52 of 230 CPU-ms).
  const __m128i line_end = _mm_set1_epi8('\n');
  while (chunk.size() - i >= 16) {
    __m128i counters = _mm_setzero_si128();
    const std::size_t steps = std::min<std::size_t>(255, (chunk.size() - i) / 16);
    for (std::size_t step = 0; step < steps; ++step, i += 16) {
      const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(chunk.data() + i));
      counters = _mm_sub_epi8(counters, _mm_cmpeq_epi8(bytes, line_end));
    }
    const __m128i sums = _mm_sad_epu8(counters, _mm_setzero_si128());
    count += static_cast<std::size_t>(_mm_cvtsi128_si64(sums)) + static_cast<std::size_t>(_mm_extract_epi16(sums, 4));
  }
#else
  // Eight bytes a step: a zero byte of w ^ 0x0a..0a is one, marked 0x80 by zero_bytes; the marks
  // summed by a multiplication.
  for (; i + 8 <= chunk.size(); i += 8) {
    std::uint64_t word = 0;
    std::memcpy(&word, chunk.data() + i, 8);
    const std::uint64_t zero = zero_bytes(word ^ (kOnes * '\n'));
    count += static_cast<std::size_t>(((zero >> 7) * kOnes) >> 56);  // the sum of the marks' bytes
  }
#endif
  for (; i < chunk.size(); ++i) count += chunk[i] == '\n' ? 1 : 0;
  return count + 1;
}

void parse_rows(std::string_view chunk, std::size_t first_line, const RowLayout& layout, RowChunk& result) {
  // Every row is a line: the columns have room for all lines, so that a row is stored by index,
  // not by push_back.
  const std::vector<double*>& column_data = result.columns;
  if (layout.record_row_lines) result.row_lines.reserve(line_capacity(chunk));
  std::size_t row_count = 0;
  Line row{};
  std::vector<Field> fields;
  const std::vector<int> slots = plain_slots(layout);
  std::vector<double> values(layout.positions.size());
  const char* const chunk_end = chunk.data() + chunk.size();
  std::size_t line_number = first_line - 1;
  try {
    for (const char* p = chunk.data(); p < chunk_end;) {
      ++line_number;
      const char* stop = slots.empty() ? nullptr : parse_plain_row(p, chunk_end, layout, slots, values.data());
      if (stop == nullptr) {
        const void* newline = std::memchr(p, '\n', static_cast<std::size_t>(chunk_end - p));
        stop = newline != nullptr ? static_cast<const char*>(newline) : chunk_end;
        std::size_t length = static_cast<std::size_t>(stop - p);
        if (length > 0 && p[length - 1] == '\r') --length;
        row = {std::string_view(p, length), line_number};
        p = stop == chunk_end ? chunk_end : stop + 1;
        if (is_skipped(row.text, layout.comment)) continue;
        split(row.text, layout.delimiter, fields, layout.source, row.number);
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
          values[k] = *value;
        }
      } else {
        p = stop == chunk_end ? chunk_end : stop + 1;  // past the '\n'
      }
      for (std::size_t k = 0; k < values.size(); ++k) column_data[k][row_count] = values[k];
      if (layout.record_row_lines) result.row_lines.push_back(line_number);
      if (row_count++ == 0) result.first_line = line_number;
    }
  } catch (...) {
    result.error = std::current_exception();
  }
  result.row_count = row_count;
}

}  // namespace inertest::io_detail

namespace inertest {

std::vector<TextField> split_text_line(std::string_view line, char delimiter, const std::string& source,
                                       std::size_t line_number) {
  std::vector<io_detail::Field> fields;
  io_detail::split(line, delimiter, fields, source, line_number);
  std::vector<TextField> result;
  result.reserve(fields.size());
  for (const auto& field : fields) {
    io_detail::check_no_stray_quote(source, line_number, field);
    result.push_back({field.value(), field.column});
  }
  return result;
}

std::vector<TextCellRow> split_text_cells(std::string_view text, const std::string& source) {
  std::vector<TextCellRow> rows;
  io_detail::LineCursor cursor(without_byte_order_mark(text));
  char delimiter = '\0';
  while (const std::optional<io_detail::Line> line = io_detail::next_content_line(cursor, '#')) {
    if (rows.empty() && delimiter == '\0' && (delimiter = io_detail::excel_separator(line->text)) != '\0') continue;
    if (delimiter == '\0') delimiter = io_detail::detect_delimiter(line->text);
    rows.push_back({line->number, split_text_line(line->text, delimiter, source, line->number)});
  }
  return rows;
}

}  // namespace inertest

#include "inertest/allan/rate_record.h"

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fast_float/fast_float.h>
#include <memory>
#include <vector>

#include "inertest/core/error.h"

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

// Text records: the first non-comment line fixes the delimiter and whether a header is present.
class TextParser {
 public:
  TextParser(const RateRecordSource& source, const SampleSink& sink) : source_(source), sink_(sink) {
    samples_.reserve(kBatch);
  }

  void line(std::string_view text) {
    ++line_number_;
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    std::size_t start = 0;
    while (start < text.size() && (text[start] == ' ' || text[start] == '\t')) ++start;
    if (start == text.size() || text[start] == '#') return;
    if (!configured_) {
      configure(text);
      if (header_) return;
    }
    const std::size_t begin = field_start(text);
    std::size_t end = begin;
    while (end < text.size() && !is_separator(text[end])) ++end;
    std::string_view field = text.substr(begin, end - begin);
    while (!field.empty() && field.back() == ' ') field.remove_suffix(1);
    double value = 0.0;
    const auto [stop, error] = fast_float::from_chars(field.data(), field.data() + field.size(), value);
    if (field.empty() || error != std::errc() || stop != field.data() + field.size() || !std::isfinite(value)) {
      fail(begin, "'" + std::string(field) + "' is not a finite number");
    }
    samples_.push_back(value);
    ++count_;
    if (samples_.size() == kBatch) flush();
  }

  std::size_t finish() {
    flush();
    if (count_ == 0) throw Error(SourceLocation{source_.path, 0, 0}, "no data rows");
    return count_;
  }

 private:
  static constexpr std::size_t kBatch = 1u << 16;

  bool is_separator(char c) const { return delimiter_ == ' ' ? (c == ' ' || c == '\t') : c == delimiter_; }

  [[noreturn]] void fail(std::size_t column, const std::string& message) const {
    throw Error(SourceLocation{source_.path, line_number_, column + 1}, message);
  }

  std::vector<std::pair<std::size_t, std::string_view>> split(std::string_view text) const {
    std::vector<std::pair<std::size_t, std::string_view>> fields;
    std::size_t i = 0;
    while (true) {
      if (delimiter_ == ' ') {
        while (i < text.size() && is_separator(text[i])) ++i;
        if (i == text.size()) break;
      }
      std::size_t end = i;
      while (end < text.size() && !is_separator(text[end])) ++end;
      std::string_view field = text.substr(i, end - i);
      std::size_t begin = i;
      while (!field.empty() && field.front() == ' ') {
        field.remove_prefix(1);
        ++begin;
      }
      while (!field.empty() && field.back() == ' ') field.remove_suffix(1);
      fields.emplace_back(begin, field);
      if (end == text.size()) break;
      i = end + 1;
    }
    return fields;
  }

  void configure(std::string_view text) {
    configured_ = true;
    delimiter_ = text.find(',') != std::string_view::npos   ? ','
                 : text.find('\t') != std::string_view::npos ? '\t'
                 : text.find(';') != std::string_view::npos  ? ';'
                                                             : ' ';
    const auto fields = split(text);
    for (const auto& [position, field] : fields) {
      double value = 0.0;
      const auto [stop, error] = fast_float::from_chars(field.data(), field.data() + field.size(), value);
      if (error != std::errc() || stop != field.data() + field.size()) header_ = true;
    }
    columns_ = fields.size();
    if (!source_.column) {
      if (columns_ != 1) {
        std::string names;
        for (const auto& [position, field] : fields) names += (names.empty() ? "" : ", ") + std::string(field);
        fail(0, "the record has " + std::to_string(columns_) + " columns (" + names +
                    "): choose one with --column (plan key `column`)");
      }
      column_ = 0;
      return;
    }
    const ColumnSelector& selector = *source_.column;
    if (selector.index > 0) {
      if (selector.index > columns_) {
        fail(0, "column " + std::to_string(selector.index) + " does not exist: the record has " +
                    std::to_string(columns_) + " columns");
      }
      column_ = selector.index - 1;
      return;
    }
    if (!header_) fail(0, "column '" + selector.name + "' is chosen by name but the record has no header row");
    for (std::size_t c = 0; c < fields.size(); ++c) {
      if (fields[c].second == selector.name) {
        column_ = c;
        return;
      }
    }
    std::string names;
    for (const auto& [position, field] : fields) names += (names.empty() ? "" : ", ") + std::string(field);
    fail(0, "no column named '" + selector.name + "' (columns: " + names + ")");
  }

  // Byte offset of the chosen field in the line.
  std::size_t field_start(std::string_view text) const {
    std::size_t i = 0;
    if (delimiter_ == ' ') {
      for (std::size_t c = 0;; ++c) {
        while (i < text.size() && is_separator(text[i])) ++i;
        if (i == text.size()) fail(i, "missing column " + std::to_string(column_ + 1));
        if (c == column_) return i;
        while (i < text.size() && !is_separator(text[i])) ++i;
      }
    }
    for (std::size_t c = 0; c < column_; ++c) {
      const std::size_t next = text.find(delimiter_, i);
      if (next == std::string_view::npos) fail(text.size(), "missing column " + std::to_string(column_ + 1));
      i = next + 1;
    }
    while (i < text.size() && text[i] == ' ') ++i;
    return i;
  }

  void flush() {
    if (!samples_.empty()) sink_(samples_);
    samples_.clear();
  }

  const RateRecordSource& source_;
  const SampleSink& sink_;
  std::vector<double> samples_;
  std::size_t line_number_ = 0;
  std::size_t count_ = 0;
  bool configured_ = false;
  bool header_ = false;
  char delimiter_ = ',';
  std::size_t columns_ = 0;
  std::size_t column_ = 0;
};

std::size_t read_text(const RateRecordSource& source, const SampleSink& sink) {
  File file = open(source.path);
  TextParser parser(source, sink);
  std::vector<char> buffer(kChunkBytes);
  std::size_t carried = 0;
  while (true) {
    if (carried == buffer.size()) buffer.resize(2 * buffer.size());  // a line longer than the buffer
    const std::size_t got = std::fread(buffer.data() + carried, 1, buffer.size() - carried, file.get());
    if (got == 0 && std::ferror(file.get())) throw Error(SourceLocation{source.path, 0, 0}, "read error");
    const std::size_t available = carried + got;
    std::string_view text(buffer.data(), available);
    std::size_t start = 0;
    while (true) {
      const std::size_t newline = text.find('\n', start);
      if (newline == std::string_view::npos) break;
      parser.line(text.substr(start, newline - start));
      start = newline + 1;
    }
    if (got == 0) {
      if (start < available) parser.line(text.substr(start));
      break;
    }
    carried = available - start;
    std::memmove(buffer.data(), buffer.data() + start, carried);
  }
  return parser.finish();
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

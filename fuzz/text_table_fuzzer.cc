// Fuzzes the text reader: any bytes must give a table or an inertest::Error, never a crash, a hang
// or another exception. The first byte picks the options (delimiter, header mode, columns); the
// rest is parsed twice, once on one thread and once cut into tiny chunks on three threads, and the
// two must agree exactly (values, line numbers, or the error message). With columns chosen, a third
// parse asks for the first of them again, which keeps every row off the plain path: the general
// path must agree too.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "inertest/core/error.h"
#include "inertest/io/text_table.h"

namespace {

// The table's rows, first line, the values of its first `columns` columns (all by default) and its
// row lines, or the error message.
std::string parse(std::string_view text, const inertest::TextTableOptions& options,
                  std::size_t columns = static_cast<std::size_t>(-1)) {
  try {
    const inertest::TextTable table = inertest::parse_text_table(text, "fuzz.csv", options);
    std::string digest = std::to_string(table.rows()) + "@" + std::to_string(table.first_data_line);
    for (std::size_t c = 0; c < table.columns.size() && c < columns; ++c) {
      for (double v : table.columns[c]) {
        char exact[32];
        std::snprintf(exact, sizeof exact, ",%a", v);  // every bit: the paths must agree exactly
        digest += exact;
      }
    }
    for (std::size_t line : table.row_lines) digest += ";" + std::to_string(line);
    return digest;
  } catch (const inertest::Error& e) {
    return std::string("error: ") + e.what();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t knobs = data[0];
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  inertest::TextTableOptions options;
  constexpr char kDelimiters[] = {'\0', ',', ';', '\t'};
  options.delimiter = kDelimiters[knobs & 3];
  options.header = static_cast<inertest::TextTableOptions::Header>((knobs >> 2) % 3);
  if (knobs & 0x40) options.columns = {inertest::ColumnSelector{"b", 0}, inertest::ColumnSelector{"", 1}};
  options.minimum_rows = (knobs & 0x80) ? 3 : 1;

  options.threads = 1;
  const std::string single = parse(text, options);
  options.threads = 3;
  options.minimum_chunk_bytes = 1;
  const std::string chunked = parse(text, options);
  if (single != chunked) std::abort();  // the chunked parse must not depend on where the chunks fall
  if (!options.columns.empty()) {
    inertest::TextTableOptions general = options;
    general.columns.push_back(options.columns.front());
    if (parse(text, general, options.columns.size()) != chunked) std::abort();  // plain and general paths agree
  }
  return 0;
}

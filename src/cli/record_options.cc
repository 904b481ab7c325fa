#include "record_options.h"

#include <charconv>
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"

namespace inertest::cli {

void add_record_options(CLI::App& command, OutputRecordSource& source) {
  command.add_option("--column", source.column,
                     "the output column of a text record by header name or 1-based index (default: the only column, "
                     "or the one headed 'output'), or the channel of a .mat, HDF5 or TDMS record (struct.field, "
                     "group/channel)");
  command.add_option("--format", source.format,
                     "auto (default: .mat, HDF5 or TDMS by magic bytes, else text), csv, mat, hdf5, tdms, or binary: "
                     "f64, f32, i32 or i16, optionally with le/be (e.g. f32be)");
}

std::pair<double, std::string> parse_number_and_file(const std::string& text, const std::string& option,
                                                     const std::string& example) {
  const auto colon = text.find(':');
  double number = 0.0;
  const char* end = text.data() + (colon == std::string::npos ? 0 : colon);
  // A number out of a double's range (1e400) left `number` at 0 with the end reached: a run at 0.
  const auto parsed = std::from_chars(text.data(), end, number);
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size() || parsed.ptr != end ||
      parsed.ec != std::errc() || !std::isfinite(number)) {
    throw Error(fmt::format("{} '{}': expected NUMBER:FILE with a finite NUMBER, e.g. {}", option, text, example));
  }
  return {number, text.substr(colon + 1)};
}

}  // namespace inertest::cli

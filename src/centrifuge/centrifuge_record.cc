#include "inertest/centrifuge/centrifuge_record.h"

#include <algorithm>
#include <fmt/format.h>

#include "inertest/io/angle_column.h"
#include "inertest/io/mapped_file.h"
#include "inertest/io/text_table.h"

namespace inertest::centrifuge {
namespace {

constexpr std::array<const char*, 7> kHarmonicColumns = {"accel_g", "beta_deg", "k0", "k1c", "k1s", "k2c", "k2s"};
constexpr std::array<const char*, 4> kSampleColumns = {"accel_g", "beta_deg", "gamma_deg", "output"};
constexpr const char* kOmegaColumn = "omega_rad_s";

// 1-based number of the header line: the first line that is neither blank nor a comment.
std::size_t header_line(std::string_view text) {
  std::size_t number = 0;
  std::size_t start = 0;
  while (start <= text.size()) {
    ++number;
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view line = text.substr(start, end - start);
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first != std::string_view::npos && line[first] != '#') return number;
    start = end + 1;
  }
  return 0;
}

template <std::size_t N>
std::string joined(const std::array<const char*, N>& names) {
  std::string text;
  for (const char* n : names) text += (text.empty() ? "" : ",") + std::string(n);
  return text;
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& n : names) text += (text.empty() ? "" : ",") + n;
  return text;
}

// Checks that the header holds exactly the required columns plus, optionally, omega_rad_s.
template <std::size_t N>
void check_columns(const TextTable& table, const std::array<const char*, N>& required, const SourceLocation& header,
                   const char* kind) {
  for (const char* name : required) {
    if (!table.has_column(name)) {
      throw Error(header, fmt::format("a {} record needs the column '{}' (header: {}; expected {}[,{}])", kind, name,
                                      joined(table.names), joined(required), kOmegaColumn));
    }
  }
  for (const std::string& name : table.names) {
    const bool known = name == kOmegaColumn || std::any_of(required.begin(), required.end(),
                                                           [&](const char* r) { return name == r; });
    if (!known) {
      throw Error(header, fmt::format("unknown column '{}' in a {} record (expected {}[,{}])", name, kind,
                                      joined(required), kOmegaColumn));
    }
  }
}

}  // namespace

std::vector<CentrifugeRun> CentrifugeRecord::runs() const {
  return kind == Kind::kHarmonics ? harmonic_runs : analyse_sample_runs(sample_runs);
}

CentrifugeRecord read_centrifuge_record(const std::string& path) {
  const MappedFile file(path);
  return parse_centrifuge_record(file.text(), path);
}

CentrifugeRecord parse_centrifuge_record(std::string_view text, const std::string& source) {
  TextTableOptions options;
  options.header = TextTableOptions::Header::kPresent;
  const TextTable table = parse_text_table(text, source, options);
  const SourceLocation header{source, header_line(text), 0};
  const auto location_of_row = [&](std::size_t row) { return SourceLocation{source, table.row_lines[row], 0}; };
  const bool has_omega = table.has_column(kOmegaColumn);
  const auto omega_of_row = [&](std::size_t row) {
    return has_omega ? std::optional<double>(table.column(kOmegaColumn)[row]) : std::nullopt;
  };

  CentrifugeRecord record;
  if (table.has_column("beta_deg")) check_degrees_not_radians(table, "beta_deg");
  if (table.has_column("gamma_deg") || table.has_column("output")) {
    check_columns(table, kSampleColumns, header, "raw-sample");
    record.kind = CentrifugeRecord::Kind::kSamples;
    const auto& accel = table.column("accel_g");
    const auto& beta = table.column("beta_deg");
    const auto& gamma = table.column("gamma_deg");
    const auto& output = table.column("output");
    for (std::size_t row = 0; row < table.rows(); ++row) {
      auto run = std::find_if(record.sample_runs.begin(), record.sample_runs.end(), [&](const CentrifugeSampleRun& r) {
        return r.accel_g == accel[row] && r.beta_rad == beta[row] * constants::kDegree;
      });
      if (run == record.sample_runs.end()) {
        record.sample_runs.push_back(
            {accel[row], omega_of_row(row), beta[row] * constants::kDegree, {}, {}, location_of_row(row)});
        run = std::prev(record.sample_runs.end());
      } else if (run->omega_rad_s != omega_of_row(row)) {
        throw Error(location_of_row(row),
                    fmt::format("omega_rad_s {} differs from {} of the run that starts at {}", *omega_of_row(row),
                                *run->omega_rad_s, run->location.to_string()));
      }
      run->gamma_rad.push_back(gamma[row] * constants::kDegree);
      run->output.push_back(output[row]);
    }
  } else if (table.has_column("k0")) {
    check_columns(table, kHarmonicColumns, header, "harmonic-amplitude");
    record.kind = CentrifugeRecord::Kind::kHarmonics;
    for (std::size_t row = 0; row < table.rows(); ++row) {
      CentrifugeRun run;
      run.accel_g = table.column("accel_g")[row];
      run.beta_rad = table.column("beta_deg")[row] * constants::kDegree;
      run.omega_rad_s = omega_of_row(row);
      for (std::size_t h = 0; h < kHarmonicCount; ++h) run.amplitudes[h] = table.column(harmonic_name(h))[row];
      run.location = location_of_row(row);
      record.harmonic_runs.push_back(run);
    }
  } else {
    throw Error(header, fmt::format("cannot tell the kind of centrifuge record from its header ({}): harmonic "
                                    "amplitudes have the columns {}, raw samples {}",
                                    joined(table.names), joined(kHarmonicColumns), joined(kSampleColumns)));
  }
  return record;
}

}  // namespace inertest::centrifuge

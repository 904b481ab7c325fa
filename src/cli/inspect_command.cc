// inertest inspect FILE: what a record holds (rows, columns, and per column count, mean, standard
// deviation, min, max), read exactly as the procedures read it. A first look at lab data.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>

#include "command.h"
#include "inertest/io/binary_record.h"
#include "inertest/io/text_table.h"
#include "inertest/numerics/statistics.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string file;
  std::string format = "csv";
  std::size_t channels = 1;
  bool json = false;
};

nlohmann::json describe(const std::string& name, const std::vector<double>& values) {
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  nlohmann::json column = {{"name", name}, {"count", values.size()}, {"mean", mean(values)},
                           {"min", *low},  {"max", *high}};
  if (values.size() > 1) column["standard_deviation"] = sample_standard_deviation(values);
  return column;
}

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "inspect",
      "Read a record as the procedures do and describe it: rows, columns, and per column the count,\n"
      "mean, standard deviation (n-1), min and max, in the record's own units. Text records: CSV, TSV,\n"
      "semicolon or whitespace separated, header optional, '#' comments. Binary: --format f64|f32|i32|i16\n"
      "(suffix be for big endian) with --channels interleaved channels.");
  command->add_option("FILE", arguments->file, "record to read")->required();
  command->add_option("--format", arguments->format, "csv (any text table) or a binary sample type")
      ->capture_default_str();
  command->add_option("--channels", arguments->channels, "interleaved channels of a binary record")
      ->capture_default_str();
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    nlohmann::json columns = nlohmann::json::array();
    std::size_t rows = 0;
    if (arguments->format == "csv") {
      TextTableOptions options;
      options.record_row_lines = false;
      const TextTable table = read_text_table(arguments->file, options);
      rows = table.rows();
      for (std::size_t i = 0; i < table.columns.size(); ++i) {
        columns.push_back(describe(table.names[i].empty() ? std::to_string(i + 1) : table.names[i], table.columns[i]));
      }
    } else {
      BinaryFormat format = BinaryFormat::parse(arguments->format);
      format.channels = arguments->channels;
      for (std::size_t c = 0; c < format.channels; ++c) {
        format.channel = c;
        const auto values = read_binary_record(arguments->file, format);
        rows = values.size();
        columns.push_back(describe(std::to_string(c + 1), values));
      }
    }
    const nlohmann::json json = {{"file", arguments->file}, {"rows", rows}, {"columns", columns}};
    std::string report = fmt::format("{}: {} rows, {} columns\n", arguments->file, rows, columns.size());
    for (const auto& c : columns) {
      report += fmt::format("  {:<16} mean {:<14.8g} sd {:<12.6g} min {:<14.8g} max {:.8g}\n",
                            c["name"].get<std::string>(), c["mean"].get<double>(),
                            c.value("standard_deviation", 0.0), c["min"].get<double>(), c["max"].get<double>());
    }
    print_result(json, report, arguments->json);
    return 0;
  };
}

const bool registered = register_command("inspect", setup);

}  // namespace
}  // namespace inertest::cli

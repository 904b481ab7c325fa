// inertest scale-factor POINTS.csv [--json]
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/io/text_table.h"
#include "inertest/procedures/scale_factor.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string points_file;
  ScaleFactorOptions options;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "scale-factor",
      "Scale factor K, zero offset F0, nonlinearity, asymmetry (GJB 2426A-2004 5.8.1-5.8.3, eqs. 1-11).\n"
      "POINTS has the header 'rate,output': one row per test point in test order; rate is the table\n"
      "rate (signed, --rate-unit, default deg/s), output the mean instrument output at that rate.\n"
      "Zero-rate rows before the first and after the last nonzero rate are the static runs.\n"
      "Outputs: scale_factor (output unit per rate unit), zero_offset, nonlinearity (ppm),\n"
      "asymmetry (ppm), scale_factor_positive, scale_factor_negative, nonlinearity_curve.");
  command->add_option("POINTS", arguments->points_file, "CSV of test points (rate,output)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--rate-unit", arguments->options.rate_unit, "unit of the rate column")
      ->capture_default_str();
  command->add_option("--output-unit", arguments->options.output_unit, "instrument output unit, e.g. pulse/s or V")
      ->capture_default_str();
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    TextTableOptions read;
    read.columns = {ColumnSelector{"rate"}, ColumnSelector{"output"}};
    read.header = TextTableOptions::Header::kPresent;
    const TextTable table = read_text_table(arguments->points_file, read);
    std::vector<ScaleFactorPoint> points(table.rows());
    for (std::size_t i = 0; i < points.size(); ++i) points[i] = {table.columns[0][i], table.columns[1][i]};
    const ScaleFactorResult result =
        with_file_context(arguments->points_file, [&] { return scale_factor(points, arguments->options); });
    print_result(result.to_json(), result.report(), arguments->json);
    return 0;
  };
}

const bool registered = register_command("scale-factor", setup);

}  // namespace
}  // namespace inertest::cli

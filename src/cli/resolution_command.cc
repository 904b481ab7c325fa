// inertest resolution STEPS.csv --scale-factor K [--rate-unit U] [--json]
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/io/text_table.h"
#include "inertest/procedures/resolution.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string file;
  ResolutionOptions options;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "resolution",
      "Resolution (GJB 2426A-2004 5.11, 50 % criterion of eq. 18), K in output units per deg/s.\n"
      "STEPS has the header 'base_rate,base_output,rate,output': one row per increment, the base rate\n"
      "(its sign gives the direction) and its mean output measured before the increment, then the\n"
      "rate with the increment and its mean output; rates in --rate-unit (default deg/s).\n"
      "JSON: resolution (deg/h), branches (forward, reverse) with every increment.");
  command->add_option("STEPS", arguments->file, "CSV of increments")->required()->check(CLI::ExistingFile);
  command->add_option("--scale-factor", arguments->options.scale_factor, "K, output units per deg/s")->required();
  command->add_option("--rate-unit", arguments->options.rate_unit, "unit of the rate columns")->capture_default_str();
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    arguments->options.validate();
    TextTableOptions read;
    read.header = TextTableOptions::Header::kPresent;
    read.columns = {ColumnSelector{"base_rate"}, ColumnSelector{"base_output"}, ColumnSelector{"rate"},
                    ColumnSelector{"output"}};
    const TextTable table = read_text_table(arguments->file, read);
    std::vector<ResolutionStep> steps;
    for (std::size_t i = 0; i < table.rows(); ++i) {
      steps.push_back({table.columns[0][i], table.columns[1][i], table.columns[2][i], table.columns[3][i]});
    }
    const ResolutionResult result = resolution(steps, arguments->options);
    print_result(result.to_json(), result.report(), arguments->json);
    return 0;
  };
}

const bool registered = register_command("resolution", setup);

}  // namespace
}  // namespace inertest::cli

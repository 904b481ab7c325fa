// inertest polarity (--positive-file F | --positive-output X) (--negative-file F | --negative-output X)
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/core/error.h"
#include "inertest/numerics/statistics.h"
#include "inertest/procedures/polarity.h"
#include "record_options.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string positive_file;
  std::string negative_file;
  std::optional<double> positive_output;
  std::optional<double> negative_output;
  std::string expected;
  OutputRecordSource source;
  PolarityOptions options;
  bool json = false;
};

double mean_output(const std::string& file, const std::optional<double>& value, const OutputRecordSource& base,
                   const char* which) {
  if (!file.empty() && value) throw Error(std::string("polarity: give a ") + which + " file or a " + which + " output, not both");
  if (value) return *value;
  if (file.empty()) throw Error(std::string("polarity: missing the ") + which + "-rate record (--" + which + "-file or --" + which + "-output)");
  OutputRecordSource source = base;
  source.path = file;
  return mean(read_output_record(source));
}

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "polarity",
      "Polarity (GJB 2426A-2004 5.7): the sign of the output change for a positive input about the IRA,\n"
      "sign(F(+) - F(-)), from records (their means) or mean outputs at +rate and -rate.\n"
      "JSON: polarity (\"positive\"/\"negative\"), sign, output_positive_rate, output_negative_rate,\n"
      "output_sign_positive_rate, output_sign_negative_rate, signs_opposite, pass (with --expected).");
  command->add_option("--positive-file", arguments->positive_file, "record at the positive rate");
  command->add_option("--negative-file", arguments->negative_file, "record at the negative rate");
  command->add_option("--positive-output", arguments->positive_output, "mean output at the positive rate");
  command->add_option("--negative-output", arguments->negative_output, "mean output at the negative rate");
  command->add_option("--expected", arguments->expected, "the specified polarity: positive or negative")
      ->check(CLI::IsMember({"positive", "negative"}));
  command->add_option("--output-unit", arguments->options.output_unit, "instrument output unit")->capture_default_str();
  add_record_options(*command, arguments->source);
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    PolarityOptions options = arguments->options;
    if (!arguments->expected.empty()) options.expected = arguments->expected == "positive" ? 1 : -1;
    const double positive = mean_output(arguments->positive_file, arguments->positive_output, arguments->source, "positive");
    const double negative = mean_output(arguments->negative_file, arguments->negative_output, arguments->source, "negative");
    const PolarityResult result = polarity(positive, negative, options);
    print_result(result.to_json(), result.report(), arguments->json);
    return 0;
  };
}

const bool registered = register_command("polarity", setup);

}  // namespace
}  // namespace inertest::cli

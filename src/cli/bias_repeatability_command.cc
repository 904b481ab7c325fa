// inertest bias-repeatability FILE... --scale-factor K [--json]
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/core/error.h"
#include "inertest/procedures/bias.h"
#include "inertest/procedures/bias_repeatability.h"
#include "record_options.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::vector<std::string> files;
  OutputRecordSource source;
  BiasOptions options;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "bias-repeatability",
      "Bias repeatability (GJB 2426A-2004 5.12.3, eq. 21): the standard deviation (Q-1) of the biases\n"
      "of Q runs (Q >= 6 asked for; at least 2 needed), each bias = mean output / K in deg/h (eq. 19).\n"
      "Each FILE is one run's output record (one column, or --column; or binary with --format).\n"
      "JSON: bias_repeatability, mean_bias (deg/h), run_biases.");
  command->add_option("FILE", arguments->files, "one output record per run")->required()->check(CLI::ExistingFile);
  command->add_option("--scale-factor", arguments->options.scale_factor, "K, output units per deg/s");
  command->add_flag("--input-deg-h", arguments->options.input_in_deg_h, "the records hold rate in deg/h already");
  add_record_options(*command, arguments->source);
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    std::vector<double> biases;
    for (const auto& file : arguments->files) {
      OutputRecordSource source = arguments->source;
      source.path = file;
      biases.push_back(bias_deg_h(read_output_record(source), arguments->options));
    }
    const BiasRepeatabilityResult result = bias_repeatability(biases);
    print_result(result.to_json(), result.report(), arguments->json);
    return 0;
  };
}

const bool registered = register_command("bias-repeatability", setup);

}  // namespace
}  // namespace inertest::cli

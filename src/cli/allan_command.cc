// inertest allan FILE --rate HZ [--format csv|f64|f32] [--column N] [--taus SPEC] [--input-unit U]
//                [--estimators LIST] [--threads N] [--json]
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/allan/allan.h"

namespace inertest::cli {
namespace {

struct Arguments {
  RateRecordSource source;
  std::string format = "csv";
  std::string column;
  std::string estimators = "all";
  AllanOptions options;
  bool json = false;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "allan",
      "Allan variance of a rate record (GJB 2426A-2004 5.12.5.4.2, IEEE Std 952-1997 Annex C, NIST SP 1065):\n"
      "ADEV, OADEV, MDEV, HDEV, OHDEV, TOTDEV with chi-squared bounds, and the noise terms Q, N (ARW),\n"
      "B (bias instability), K (RRW), R (rate ramp) by the fit of GJB eq. (30) and by slope read-off.\n"
      "FILE: one channel of rate samples, text (csv) or raw little-endian f64/f32. Streams the file twice.");
  command->add_option("FILE", arguments->source.path, "rate record")->required()->check(CLI::ExistingFile);
  command->add_option("--rate", arguments->options.sample_rate_hz, "sample rate in Hz")->required();
  command->add_option("--format", arguments->format, "csv, f64 or f32 (raw little-endian)")->capture_default_str();
  command->add_option("--column", arguments->column, "text column: header name or 1-based index");
  command->add_option("--taus", arguments->options.taus, "octave, decade, all, N/decade or a list of tau in s")
      ->capture_default_str();
  command->add_option("--input-unit", arguments->options.input_unit, "unit of the samples")->capture_default_str();
  command->add_option("--estimators", arguments->estimators, "comma list of adev,oadev,mdev,hdev,ohdev,totdev")
      ->capture_default_str();
  command->add_option("--threads", arguments->options.worker_count, "worker threads")->capture_default_str();
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    arguments->source.format = parse_rate_record_format(arguments->format);
    if (!arguments->column.empty()) arguments->source.column = ColumnSelector::parse(arguments->column);
    arguments->options.estimators = EstimatorSet::parse(arguments->estimators);
    const AllanResult result = allan_variance_of_file(arguments->source, arguments->options, terminal_progress());
    print_result(result.to_json(), result.report(), arguments->json);
    return 0;
  };
}

const bool registered = register_command("allan", setup);

}  // namespace
}  // namespace inertest::cli

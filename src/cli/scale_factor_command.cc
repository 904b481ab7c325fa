// inertest scale-factor POINTS.csv [--json]
// inertest scale-factor --record FILE --sample-rate HZ [--rate-column NAME] [--output-column NAME] ...
// inertest scale-factor --records LIST.csv --sample-rate HZ [--output-column NAME] [--settling-time S]
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/core/error.h"
#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/scale_factor.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string points_file;
  std::string record_file;
  std::string records_listing;
  std::string rate_column = "rate";
  std::string output_column = "output";
  RateSegmentOptions segments;
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
      "Instead of POINTS, raw records (the mean after --settling-time is F_j of eq. 1):\n"
      "  --record FILE: one long record with a table-rate column (--rate-column) and the output\n"
      "    (--output-column), cut into constant-rate segments: rates within --rate-tolerance of the\n"
      "    segment's first rate belong to it, segments shorter than --minimum-segment s are skipped\n"
      "    (ramps), and a segment whose rate is within the tolerance of zero is a static run.\n"
      "  --records LIST: a CSV with the header 'rate,file', one record per test point in test\n"
      "    order (paths relative to LIST), each with the output column --output-column.\n"
      "  Both need --sample-rate (Hz). Columns are header names or 1-based indexes.\n"
      "Outputs: scale_factor (output unit per rate unit), zero_offset, nonlinearity (ppm),\n"
      "asymmetry (ppm), scale_factor_positive, scale_factor_negative, nonlinearity_curve.");
  command->add_option("POINTS", arguments->points_file, "CSV of test points (rate,output)")->check(CLI::ExistingFile);
  auto* record = command->add_option("--record", arguments->record_file, "one long record with a table-rate column")
                     ->check(CLI::ExistingFile);
  auto* records = command->add_option("--records", arguments->records_listing, "CSV listing rate,file (a record per point)")
                      ->check(CLI::ExistingFile);
  record->excludes(records);
  command->add_option("--rate-column", arguments->rate_column, "table-rate column of --record")->capture_default_str();
  command->add_option("--output-column", arguments->output_column, "output column of the records")
      ->capture_default_str();
  command->add_option("--sample-rate", arguments->segments.timing.sample_rate_hz, "sample rate of the records, Hz");
  command->add_option("--settling-time", arguments->segments.timing.settling_time_s,
                      "dropped at the start of each record / after each change of rate, s")
      ->capture_default_str();
  command->add_option("--minimum-segment", arguments->segments.minimum_segment_s,
                      "shortest constant-rate segment of --record, s")
      ->capture_default_str();
  command->add_option("--rate-tolerance", arguments->segments.rate_tolerance,
                      "rate tolerance of a segment of --record, rate unit")
      ->capture_default_str();
  command->add_option("--rate-unit", arguments->options.rate_unit, "unit of the rates")->capture_default_str();
  command->add_option("--output-unit", arguments->options.output_unit, "instrument output unit, e.g. pulse/s or V")
      ->capture_default_str();
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    const auto& a = *arguments;
    const int sources = !a.points_file.empty() + !a.record_file.empty() + !a.records_listing.empty();
    if (sources != 1) throw Error("scale-factor: give exactly one of POINTS, --record FILE or --records LIST");
    std::vector<ScaleFactorPoint> points;
    if (!a.points_file.empty()) {
      points = read_scale_factor_points(a.points_file);
    } else if (!a.record_file.empty()) {
      points = read_scale_factor_record(a.record_file, a.rate_column, a.output_column, a.segments);
    } else {
      const std::vector<ListedFile> listing = read_file_listing(a.records_listing, "rate");
      points = read_scale_factor_point_records(listing, a.output_column, a.segments.timing);
    }
    const std::string& source = !a.points_file.empty() ? a.points_file
                                : !a.record_file.empty() ? a.record_file
                                                         : a.records_listing;
    const ScaleFactorResult result = with_file_context(source, [&] { return scale_factor(points, a.options); });
    print_result(result.to_json(), result.report(), a.json);
    return 0;
  };
}

const bool registered = register_command("scale-factor", setup);

}  // namespace
}  // namespace inertest::cli

// inertest threshold FILE --method 1|2|3 --scale-factor K [...]
#include <nlohmann/json.hpp>

#include "command.h"
#include "inertest/io/text_table.h"
#include "inertest/procedures/threshold.h"
#include "record_options.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string file;
  int method = 1;
  ThresholdOptions options;
  std::string criterion_denominator = "expected";
  double table_rate_deg_s = 0.0;
  std::optional<double> sample_rate_hz;
  std::string time_column;
  OutputRecordSource source;
  bool json = false;
};

std::vector<std::vector<double>> read_columns(const std::string& file, const std::vector<std::string>& names) {
  TextTableOptions read;
  read.header = TextTableOptions::Header::kPresent;
  for (const auto& n : names) read.columns.push_back(ColumnSelector{n});
  return read_text_table(file, read).columns;
}

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "threshold",
      "Threshold (GJB 2426A-2004 5.10, eqs. 14-17), K in output units per deg/s. The 50 % criterion is\n"
      "relative to the expected output (IEEE Std 952-1997) unless --criterion-denominator measured (eq. 15 as\n"
      "printed, relative to the measured output).\n"
      "--method 1: FILE has the header 'rate,output' (table rate, --rate-unit, default deg/s; mean output);\n"
      "  zero-rate rows give the zero output unless --zero.\n"
      "--method 2: FILE has the header 'angle_deg,output' (dividing-head angle of the IRA from north, plus\n"
      "  --heading; mean output); Ω = Ωe cos(latitude) cos(angle). East/west rows give the zero unless --zero.\n"
      "--method 3: FILE is the record of one slow revolution: a time column (s) and an output column, or\n"
      "  the output alone with --rate HZ; --table-rate is the rate (deg/s) at which the IRA azimuth grows,\n"
      "  --heading its azimuth at t = 0; the zero is the record's mean unless --zero.\n"
      "JSON: threshold (deg/h), method, criterion_denominator, branches (candidate per direction with every point).");
  command->add_option("FILE", arguments->file, "test points or record")->required()->check(CLI::ExistingFile);
  command->add_option("--method", arguments->method, "1 (rate table), 2 (dividing head), 3 (slow rotation)")
      ->required()
      ->check(CLI::Range(1, 3));
  command->add_option("--scale-factor", arguments->options.scale_factor, "K, output units per deg/s")->required();
  command->add_option("--zero", arguments->options.zero_output, "zero output (output at zero input)");
  command
      ->add_option("--criterion-denominator", arguments->criterion_denominator,
                   "50 % criterion relative to the 'expected' output (IEEE Std 952-1997) or the 'measured' one "
                   "(GJB 2426A eq. 15 as printed)")
      ->check(CLI::IsMember({"expected", "measured"}))
      ->capture_default_str();
  command->add_option("--rate-unit", arguments->options.rate_unit, "method 1: unit of the rate column")
      ->capture_default_str();
  command->add_option("--latitude", arguments->options.latitude_deg, "site latitude, deg (methods 2, 3)");
  command->add_option("--heading", arguments->options.heading_deg,
                      "method 2: azimuth of the dividing head's zero; method 3: IRA azimuth at t = 0 (deg)");
  command->add_option("--table-rate", arguments->table_rate_deg_s, "method 3: table rate, deg/s");
  command->add_option("--rate", arguments->sample_rate_hz, "method 3: sample rate, Hz (record without time column)");
  command->add_option("--time-column", arguments->time_column, "method 3: time column by name or 1-based index");
  add_record_options(*command, arguments->source);
  command->add_flag("--json", arguments->json, "print one JSON object on stdout");
  return [arguments] {
    ThresholdOptions options = arguments->options;
    options.criterion_denominator = parse_criterion_denominator(arguments->criterion_denominator);
    options.validate();
    ThresholdResult result;
    if (arguments->method == 1) {
      const auto columns = read_columns(arguments->file, {"rate", "output"});
      std::vector<RateTablePoint> points;
      for (std::size_t i = 0; i < columns[0].size(); ++i) points.push_back({columns[0][i], columns[1][i]});
      result = threshold_rate_table(points, options);
    } else if (arguments->method == 2) {
      const auto columns = read_columns(arguments->file, {"angle_deg", "output"});
      std::vector<DividingHeadPoint> points;
      for (std::size_t i = 0; i < columns[0].size(); ++i) points.push_back({columns[0][i], columns[1][i]});
      result = threshold_dividing_head(points, options);
    } else {
      OutputRecordSource source = arguments->source;
      source.path = arguments->file;
      const TimedRecord record = read_timed_record(source, arguments->sample_rate_hz, arguments->time_column, 4);
      result = threshold_rotating(record.time_s, record.output, arguments->table_rate_deg_s, options);
    }
    print_result(result.to_json(), result.report(), arguments->json);
    return 0;
  };
}

const bool registered = register_command("threshold", setup);

}  // namespace
}  // namespace inertest::cli

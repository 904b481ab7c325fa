#include "record_options.h"

namespace inertest::cli {

void add_record_options(CLI::App& command, OutputRecordSource& source) {
  command.add_option("--column", source.column,
                     "text record: the output column by header name or 1-based index (default: the only or first "
                     "column)");
  command.add_option("--format", source.format,
                     "binary record instead of text: f64, f32, i32 or i16, optionally with le/be (e.g. f32be)");
}

void add_axis_options(CLI::App& command, AxisOrientation& axis) {
  command.add_option("--latitude", axis.latitude_deg, "site latitude, deg (north positive)")->capture_default_str();
  command.add_option("--heading", axis.heading_deg, "azimuth of the IRA from north, deg (east positive)")
      ->capture_default_str();
  command.add_option("--elevation", axis.elevation_deg, "elevation of the IRA above the horizontal, deg")
      ->capture_default_str();
}

}  // namespace inertest::cli

// Options shared by the commands that read one instrument-output record: --column and --format,
// and the Earth-rate geometry (--latitude, --heading, --elevation).
#pragma once

#include <CLI/CLI.hpp>

#include "inertest/io/output_record.h"
#include "inertest/procedures/earth_rate.h"

namespace inertest::cli {

// Adds --column (text records) and --format (binary records) writing into source.
void add_record_options(CLI::App& command, OutputRecordSource& source);

// Adds --latitude, --heading and --elevation (deg) writing into axis.
void add_axis_options(CLI::App& command, AxisOrientation& axis);

}  // namespace inertest::cli

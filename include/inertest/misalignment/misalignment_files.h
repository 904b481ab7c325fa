// Reading the input files of the misalignment separations (the misalignment paper) into rows, with the line of
// every row kept for error messages. Shared by the CLI and the test-plan steps.
#pragma once

#include <string>
#include <vector>

#include "inertest/misalignment/accelerometer_misalignment.h"
#include "inertest/misalignment/gyro_misalignment.h"

namespace inertest {

// Means CSV with the header alpha_deg,beta_deg,rate_dps,output: one row per position and
// direction (the sign of rate_dps), outputs already averaged over whole revolutions.
std::vector<GyroMisalignmentRow> read_gyro_misalignment_positions(const std::string& path);

// Raw records: a listing CSV with the header alpha_deg,beta_deg,rate_dps,file, one row per
// position and direction; each file (relative to the listing's directory) is a record with an
// `output` column and either a `table_angle_deg` column (whole revolutions cut from the table
// angle) or a `time_s` column (cut from time and rate). Each row's output is the record's mean
// over whole revolutions (revolution_average.h); its line is the listing's line. With
// `pulse_counts` (ProcedureCall::pulse_counts) each mean is times the record's mean sample rate,
// pulse/s, and a record without `time_s` is an Error.
std::vector<GyroMisalignmentRow> read_gyro_misalignment_records(const std::string& listing_path,
                                                                bool pulse_counts = false);

// CSV with the header beta_deg,output and optionally run (an integer; all rows are run 1 without it).
std::vector<AccelerometerMisalignmentRow> read_accelerometer_misalignment_positions(const std::string& path);

}  // namespace inertest

// Readers for the input files of the scale-factor series and bandwidth/delay procedures, shared by
// their CLI commands and plan steps. Each checks what can be
// pinned to a place in a file (a frequency out of order, a file that does not exist) and throws
// Error with that file, line and column; everything else is left to the procedure.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/procedures/bandwidth_and_delay.h"
#include "inertest/procedures/rate_segments.h"
#include "inertest/procedures/scale_factor.h"

namespace inertest {

// One row of a listing: a number (rate, temperature, frequency) and a data file.
struct ListedFile {
  double key = 0.0;
  std::string path;     // resolved against the listing's directory
  SourceLocation where;  // the row in the listing
};

// The runs of a numbered runs input (ProcedureCall::runs) as listed files, each at its run's place.
std::vector<ListedFile> listed_files(std::span<const RunInput> runs);

// Throws Error at the run's place unless every listed frequency is positive and above the one
// before (GJB 2426A 5.13.3 a: frequencies in increasing order).
void check_increasing_frequencies(std::span<const ListedFile> runs);

// Reads a CSV listing with a header row naming key_column and file_column (other columns are
// ignored; '#' starts a comment line). Relative paths are taken from the listing's directory; each
// file must exist. Throws Error at the row/column of a bad number, a missing file, a wrong column
// count, or an empty listing.
std::vector<ListedFile> read_file_listing(const std::string& listing, const std::string& key_column,
                                          const std::string& file_column = "file");

// A table of test points with the header rate,output (scale-factor POINTS.csv).
std::vector<ScaleFactorPoint> read_scale_factor_points(const std::string& path);

// One long record with a table-rate column, cut into constant-rate segments (rate_segments.h).
std::vector<ScaleFactorPoint> read_scale_factor_record(const std::string& path, const std::string& rate_column,
                                                       const std::string& output_column,
                                                       const RateSegmentOptions& options);

// A record per test point: each listed file's output column, its mean after the settling time
// (eq. 1), at the listed rate, in the listed order.
std::vector<ScaleFactorPoint> read_scale_factor_point_records(std::span<const ListedFile> points,
                                                              const std::string& output_column,
                                                              const RecordTiming& timing);

// A table freq_hz,gain,phase_deg (phase of the output against the input rate, negative for a lag).
// Frequencies must be positive and increase; gains positive.
std::vector<FrequencyResponsePoint> read_frequency_response(const std::string& path);

// Angular-vibration records, one listed file per frequency (increasing), each with the columns
// time_column (s), output_column (instrument output) and angle_column (interferometer angle).
std::vector<AngularVibrationRecord> read_angular_vibration_records(std::span<const ListedFile> runs,
                                                                   const std::string& time_column,
                                                                   const std::string& output_column,
                                                                   const std::string& angle_column);

}  // namespace inertest

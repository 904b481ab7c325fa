// The Allan analysis of several channels of one record at once (issue 19): an IMU's gyro and
// accelerometer axes (gx, gy, gz, ax, ay, az) read in one pass, each analysed as `allan` analyses
// one channel (allan.h), with its own input unit. A channel in an acceleration unit gets the
// accelerometer's noise terms (velocity random walk, bias instability, acceleration random walk;
// noise_terms.h).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "inertest/allan/allan.h"
#include "inertest/core/progress.h"
#include "inertest/io/rate_record.h"
#include "inertest/io/text_table.h"

namespace inertest {

struct AllanChannel {
  std::string name;  // the header name or channel name; the selector as given when there is none
  AllanResult result;
};

struct AllanChannels {
  std::vector<AllanChannel> channels;  // in the order asked for

  // {"procedure": "allan_variance", "clause", "channels": {"gx": {the JSON of AllanResult}, ...}}.
  nlohmann::json to_json() const;
  // One table per channel, each under its name.
  std::string report() const;
};

// The options of each channel: `common` with its input unit taken from `units`, a comma list of
// NAME=UNIT (NAME a channel's name or its selector as given) and at most one bare UNIT that sets
// the unit of the channels not named (default: common.input_unit). Throws ParameterError
// ("input_unit") for a name that is no channel, a channel named twice, or a unit that does not parse.
std::vector<AllanOptions> channel_options(const AllanOptions& common, const std::vector<std::string>& names,
                                          const std::vector<std::string>& selectors, std::string_view units);

// On columns of samples in memory, of equal length. The channels are analysed side by side on
// min(channels, worker_count) threads; the results are the same whatever the count.
AllanChannels allan_variance_of_channels(const std::vector<std::span<const double>>& columns,
                                         const std::vector<std::string>& names,
                                         const std::vector<AllanOptions>& options);

// From a file, each byte read once: text is parsed once, in parallel chunks, into all the columns
// asked for (read_text_table); a record of named channels (.mat, HDF5, TDMS) streams each channel
// once (allan_variance_of_file). Raw binary records hold one channel: asking for several is an
// Error. `units` as in channel_options; a unit a channel stores or its header states is its unit
// where none is given. With `raw_output` (allan's scale_factor: common.scale turns an output into
// common.input_unit) a channel that states a rate or an acceleration is an Error (it is no raw
// output), and one that states another unit (pulse/s) is taken in common.input_unit. Errors name
// the file, line and column (or channel).
AllanChannels allan_variance_of_channels_in_file(const RateRecordSource& source,
                                                 const std::vector<ColumnSelector>& columns, std::string_view units,
                                                 const AllanOptions& common, bool raw_output,
                                                 const ProgressCallback& progress = {});

}  // namespace inertest

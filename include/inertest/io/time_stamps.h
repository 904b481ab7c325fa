// Checking the time column of a record: time stamps must increase; a step of more than 1.5 sample
// intervals is a gap (a logger that dropped samples), and of stamps rounded coarser than the interval
// (800 Hz in ms) a step longer than the interval by more than their quantum. What happens at a gap is
// the user's choice: stop with an error, split the record into its contiguous segments, or fill the
// missing samples by linear interpolation. Procedures that take a time column call
// check_time_stamps() after read_text_table() and work on the segments it returns.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "inertest/core/error.h"

#include "inertest/io/text_table.h"

namespace inertest {

enum class GapPolicy { kStop, kSplit, kInterpolate };

// "stop", "split" or "interpolate"; throws Error naming the accepted words.
GapPolicy parse_gap_policy(std::string_view text);
std::string to_string(GapPolicy policy);

struct TimeStampOptions {
  GapPolicy policy = GapPolicy::kStop;
  // The nominal sample interval in the time column's unit; absent: the median step of the record
  // (refined by the mean step between gaps where the stamps are coarse, see time_stamps.cc).
  std::optional<double> sample_interval;
  // A step longer than gap_factor sample intervals is a gap (1.5: one sample or more is missing).
  double gap_factor = 1.5;
  void validate() const;
};

// One gap: between data rows row - 1 and row (0-based rows of the record as read).
struct TimeGap {
  std::size_t row = 0;
  std::size_t line = 0;       // 1-based file line of the first sample after the gap (0: unknown)
  double time_before = 0.0;   // last time stamp before the gap
  double time_after = 0.0;    // first time stamp after it
  std::size_t missing = 0;    // samples missing: round(step / interval) - 1, at least 1
};

// Rows [begin, end) of the table as returned (after interpolation, if any) with no gap inside.
struct TimeSegment {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::size_t first_line = 0;  // file lines of its first and last samples (0: unknown)
  std::size_t last_line = 0;
  std::size_t size() const { return end - begin; }
};

struct TimeStampReport {
  GapPolicy policy = GapPolicy::kStop;
  double sample_interval = 0.0;
  std::vector<TimeGap> gaps;           // every gap, in record order
  std::vector<TimeSegment> segments;   // kSplit: one per contiguous run; otherwise one, the whole table
  std::size_t interpolated_samples = 0;  // kInterpolate: rows added in all
  nlohmann::json to_json() const;
};

// The gaps of increasing time stamps: steps longer than options.gap_factor sample intervals (the
// options' interval, else the median step; coarse stamps: see stamp_quantum), in order; `lines`
// (empty: unknown) gives the file line of each sample. The policy is not applied. Needs at least 2
// time stamps.
struct TimeGaps {
  double sample_interval = 0.0;
  // Stamps rounded coarser than the interval (800 Hz in ms: steps of 1 and 2 ms): their quantum (1 ms),
  // by which each gap's length is uncertain; the interval is then the mean step between the gaps, and a
  // gap a step longer than the interval by more than a quantum (and than gap_factor). 0 for fine stamps.
  double stamp_quantum = 0.0;
  std::vector<TimeGap> gaps;
};
TimeGaps find_time_gaps(std::span<const double> time, std::span<const std::size_t> lines,
                        const TimeStampOptions& options);

// Seconds per unit of the time stamps of a column or channel named `name`, whose file may store its
// unit (`stored_unit`, "" for none: a .mat, HDF5 or TDMS channel's): the stored unit when it is a
// time's, else the time unit the name (a channel's: its last part, "imu/time_ms") states
// ("time_ms", "t [us]", "Time (min)", as RecordTimeColumn), else 1 (s). (Stamps in ms taken as s made a turn-on time 1000 times too
// long.) Throws Error when a time's name states a unit that is no time's ("T_degC" taken as the
// time column).
double seconds_per_time_stamp(const std::string& name, const std::string& stored_unit = "");

// Returned column `column` of a text table as time stamps in s, moved out of the table: they must
// increase (require_increasing_time), converted by seconds_per_time_stamp of the column's name; no
// header: taken in s.
std::vector<double> take_time_column_s(TextTable& table, std::size_t column);

// The time column a text record's header names, and the sample interval its first rows show.
// The column is "time" or "timestamp" (taken in s), or "time", "t" or "timestamp" with a time unit in
// the name ("time_s", "t_ms", "Time (s)", "time [us]", "time/s"); "t" alone or "T_degC" names no time.
struct RecordTimeColumn {
  std::string name;             // as the header writes it
  SourceLocation header;        // the file and its header line
  bool unit_stated = false;     // false: the name states no unit, s taken
  double sample_interval_s = 0.0;  // the mean step between gaps (steps over 2.5 median steps), in s
  std::size_t rows = 0;         // the rows it was found from
  double first_s = 0.0;         // the first stamp, in s
  double last_s = 0.0;          // the last stamp of the whole record, in s (read from the file's end)

  // The rate its stamps give, to 12 significant digits: stamps of 0.01 s are 100 Hz, not the
  // 100.00000000000001 of 1 / 0.01.
  double sample_rate_hz() const;
};
// The first 256 KiB of a text record, cut after its last whole line, and its header as
// parse_text_table_header reads it; nullopt for what is not a regular file (a pipe is not read
// ahead) or not text the header parser takes.
struct RecordHead {
  std::string text;
  bool whole = false;  // the record is no longer than that
  TextTableHeader header;
};
std::optional<RecordHead> read_record_head(const std::string& path);

// Reads the first 256 KiB of the file (read_record_head), and the last 64 KiB for last_s (a rate record of 10^9 lines
// is not read twice): the first such column with at least 3 increasing numbers in the head; nullopt
// for no such column, or for what is not a regular text file.
std::optional<RecordTimeColumn> find_record_time_column(const std::string& path);

// A sample rate given for a text record (--rate, sample_rate_hz) checked against the record's own
// time column when its name states its unit ("time_s"; a "time" may hold ticks): Error at its
// header line naming both when 1/rate is off the column's interval by more than 5 % (a 10 Hz record
// analysed as 100 Hz put every tau 10x short). No such column: no check.
void check_sample_rate_against_time_column(const std::string& path, double sample_rate_hz);

// After the `rows` samples of a text record were read where the rate gives their times (a rate
// record, bias's windows, a timed record at a rate; not a record read for its mean alone):
// its time column (as above), from the first stamp to the last, must span (rows - 1) intervals of the
// column's own (its head's), within 3 intervals and 2e-4 of the span (a clock drifting over hours).
// Else an Error naming both spans: samples are missing (a gap) or the rate changes within the
// record, which the head alone cannot show (1000 of 3000 samples gone from the middle of a 10 Hz
// record went into the Allan variance without a word). A clock that wraps (seconds of the day past
// midnight) is not held to it.
void check_time_column_span(const std::string& path, std::size_t rows);

// Checks table column `time_column` (an index into table.columns) and applies the policy.
// Throws Error at the time stamp's file:line:column when time stands still or goes backwards, when
// fewer than 2 samples give no interval, and, under kStop, at the first gap (naming the line, the
// time before and after it, and the samples missing). Under kInterpolate the table grows in place:
// every column gets the missing samples by linear interpolation in time, evenly spaced across the
// gap, and row_lines gets 0 for them; filling more samples than the record holds is refused (an Error)
// rather than inventing most of a record.
TimeStampReport check_time_stamps(TextTable& table, std::size_t time_column, const TimeStampOptions& options);

}  // namespace inertest

// Reading one instrument-output record for the procedures that work on sampled output (bias,
// turn-on time, threshold method 3, polarity): a text record (one column chosen by name or
// 1-based position, optionally with a time column), a raw binary record (f64, f32, ...), or a
// channel of a MATLAB .mat, HDF5 or NI TDMS record (io/channel_record.h), found by its magic bytes.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace inertest {

struct InputSpec;
struct ProcedureCall;
struct ProcedureSpec;

struct OutputRecordSource {
  std::string path;
  // Empty or "auto": a .mat, HDF5 or TDMS record by its magic bytes, else a text record. "csv": a
  // text record; "mat", "hdf5", "tdms": that format. Otherwise a binary format as
  // BinaryFormat::parse reads it ("f64", "f32be").
  std::string format;
  // Text records: the output column by header name or 1-based index ("2"); empty means the only
  // column, or the second when a time column is read. Records of named channels: the channel by
  // name ("group/channel", "struct.field") or 1-based index; empty means the only numeric channel.
  // Ignored for binary records.
  std::string column;
  // A binary record's sample rate (Hz) where neither the command nor the step gives one: a plan's
  // [instrument] sample_rate_hz. Timed readers only; a text record keeps its time column.
  std::optional<double> instrument_sample_rate_hz;
};

// Checks a format as OutputRecordSource::format takes it; throws Error naming the formats known.
void check_output_record_format(const std::string& format);

// The output column as doubles. Throws Error naming the file (and line/column in a text record)
// when it is missing, malformed, or holds fewer than minimum_samples samples.
std::vector<double> read_output_record(const OutputRecordSource& source, std::size_t minimum_samples = 1);

// A record with the time of each sample in seconds since power-on (or since the record's start).
struct TimedRecord {
  std::vector<double> time_s;
  std::vector<double> output;
};

// With sample_rate_hz: the output column alone; sample i (0-based) gets the time (i + 1) / rate,
// the end of the interval over which the instrument accumulated it. Without: a text record with a
// time column (time_column by name or index; empty means the first column) and the output column
// (source.column; empty means the second column). Times must increase strictly; a violation is an
// Error naming the line. A record of named channels gives its time as the sample rate it stores
// (1 / wf_increment, a sample_rate_hz attribute): a sample_rate_hz that contradicts it is an Error
// naming both; without a stored rate, time_column names a channel of times, or the rate is needed.
TimedRecord read_timed_record(const OutputRecordSource& source, std::optional<double> sample_rate_hz,
                              const std::string& time_column = "", std::size_t minimum_samples = 1);

// The sample rate of a record sampled at `given` Hz: `given`, checked against the rate a record of
// named channels stores for the channel (io/channel_record.h resolve_sample_rate: a contradiction
// is an Error naming both), or against a text record's time column that states its unit
// (io/time_stamps.h check_sample_rate_against_time_column); raw binary records store none. `given`
// 0 is none given: the stored rate, else a ParameterError on sample_rate_hz.
double record_sample_rate(const OutputRecordSource& source, double given);

// The unit of a record's samples: `given`, checked against the unit a record of named channels
// stores for the channel (io/channel_record.h resolve_unit: a contradiction is an Error naming
// both; a stored unit inertest does not know yields to `given`). Text and raw binary records store
// none: `given`. Without `given`, the stored unit, if any.
std::optional<std::string> record_unit(const OutputRecordSource& source, const std::optional<std::string>& given);

// Sets the record readers of a procedure's call (read_record, read_timed_record,
// record_sample_rate and record_unit) for records stored as `source` says (its path each file's), as the command
// line, a plan step and Python give it: at least `minimum_samples` samples, timed by
// `sample_rate_hz` or the time column. An Error without a place gets the file's.
void set_record_readers(ProcedureCall& call, const OutputRecordSource& source, std::size_t minimum_samples,
                        std::optional<double> sample_rate_hz, const std::string& time_column);

// An output unit of pulse or pulses is a pulse counter read once a sample interval, and K is output
// per deg/s: the output of GJB 2426A eq. (19) is a rate. A FOG's counts per 10 ms taken as pulse/s
// gave a bias 100 times too small. For a call whose output_unit counts pulses (counts_pulses), by the
// inputs of `spec` that `given` says are given:
//  - output_unit becomes pulse/s (output_unit_as_rate: a table of mean outputs, test points or
//    positions, is taken as per second, as a lab reports a counter's means);
//  - with raw samples (InputSpec::raw_samples) call.pulse_counts is set; output records
//    (InputSpec::records) are read as pulse/s, count x the sample rate: the one given or the record
//    stores (a timed record's: its mean interval); a record without one is an Error naming it.
// Call after set_record_readers.
// Another unit, or values alone (polarity's outputs, whose sign is the same in counts): nothing.
void read_pulse_counts_as_rates(ProcedureCall& call, const ProcedureSpec& spec,
                                const std::function<bool(const InputSpec&)>& given,
                                std::optional<double> sample_rate_hz);

// The unit outputs are reported in: pulse/s for an output unit that counts pulses per sample
// interval (records are converted; a table's mean outputs, test points or positions, are taken as
// per second, as a lab reports a counter's means: a mean has no interval left to convert it by);
// another unit as it is.
std::string output_unit_as_rate(const std::string& output_unit);

// For a procedure that reads its raw records itself, when call.pulse_counts: each output times the
// record's `sample_rate_hz` (> 0), pulse/s.
void pulse_counts_as_rates(std::span<double> outputs, double sample_rate_hz);
// The same for a timed record: at `sample_rate_hz` when given, else at its mean sample rate.
void pulse_counts_as_rates(TimedRecord& record, std::optional<double> sample_rate_hz);

// The mean sample rate of time stamps (s, increasing; fewer than 2 is an Error): the steps over
// their span, leaving out the gaps (steps over 1.5 median steps, as `inspect` finds them) when they
// are a logger's dropped samples: rare, each a whole number of intervals. A pulse counter's interval
// is the nominal one: each stamp's own would carry the logger's jitter into the count, and each
// count after a gap still covers one interval (a gap kept in the span lowered the rate: 5 s lost
// from a 25 Hz IMU record made its gyro scale factors 5.3 % small).
double mean_sample_rate_hz(std::span<const double> time_s);

// For a procedure that divides the instrument's output by its scale factor K: throws Error naming
// the file when the record stores its samples in a unit of angular rate or of acceleration (HDF5
// units, TDMS unit_string) other than the instrument's `output_unit` (an instrument whose output is
// in deg/s, with a K near 1, stores that), saying `instead` what to do. Dividing a record's deg/s by
// a K of 36000 gave 0.025 deg/h for a bias of 898 deg/h, and a PASS.
void require_raw_output(const ProcedureCall& call, const std::string& file, const std::string& output_unit,
                        const std::string& instead);

}  // namespace inertest

#include "inertest/io/time_stamps.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/units.h"

namespace inertest {
namespace {

// Samples missing in a step of `ratio` sample intervals: the nearest whole number of intervals
// less one, at least one (a step of more than gap_factor intervals lost a sample). Clamped so that
// absurd steps (1e300 s) stay representable; such a gap is refused by the interpolation bound.
std::size_t missing_samples(double ratio) {
  constexpr double kLargest = 1e15;
  return static_cast<std::size_t>(std::clamp(std::round(ratio) - 1.0, 1.0, kLargest));
}

// The median of the steps between successive time stamps: the nominal interval of a record with
// a few gaps (a mean would be pulled up by them). The lower median of an even count, so that of
// two steps the shorter is the interval and the longer can be a gap.
double median_step(std::span<const double> time) {
  std::vector<double> steps(time.size() - 1);
  for (std::size_t i = 1; i < time.size(); ++i) steps[i - 1] = time[i] - time[i - 1];
  const auto middle = steps.begin() + static_cast<std::ptrdiff_t>((steps.size() - 1) / 2);
  std::nth_element(steps.begin(), middle, steps.end());
  return *middle;
}

// The median step, refined where the time stamps are coarse for their size: at 1.7e9 s (epoch
// seconds) doubles are 2.4e-7 s apart, and every step of a 1 kHz record is one of a few values
// (the median read 0.99992752 ms, 72 ppm off). Between the gaps (`gap_rows`: the rows after them)
// the steps telescope: their mean is (sum of t_end - t_start over the runs) / (steps), off by two
// roundings per run. It replaces the median when within two of the stamps' spacing of it, so a
// record whose steps truly vary (jitter, mixed intervals) keeps its median.
double refined_step(std::span<const double> time, std::span<const std::size_t> gap_rows, double median) {
  double span = 0.0;
  std::size_t steps = 0;
  std::size_t start = 0;
  const auto run_to = [&](std::size_t end) {  // the run of rows [start, end]
    span += time[end] - time[start];
    steps += end - start;
  };
  for (std::size_t row : gap_rows) {
    run_to(row - 1);
    start = row;
  }
  run_to(time.size() - 1);
  if (steps == 0) return median;
  const double largest = std::max(std::abs(time.front()), std::abs(time.back()));
  const double spacing = std::nextafter(largest, std::numeric_limits<double>::infinity()) - largest;
  const double mean = span / static_cast<double>(steps);
  return std::abs(mean - median) <= 2.0 * spacing ? mean : median;
}

std::size_t line_of(const TextTable& table, std::size_t row) {
  return row < table.row_lines.size() ? table.row_lines[row] : 0;
}

void interpolate_gaps(TextTable& table, const std::vector<TimeGap>& gaps, std::size_t time_column) {
  std::size_t added = 0;
  for (const auto& gap : gaps) added += gap.missing;
  const std::size_t rows = table.rows();
  const bool lines = !table.row_lines.empty();
  std::vector<std::vector<double>> columns(table.columns.size());
  for (auto& c : columns) c.reserve(rows + added);
  std::vector<std::size_t> row_lines;
  if (lines) row_lines.reserve(rows + added);
  auto gap = gaps.begin();
  for (std::size_t i = 0; i < rows; ++i) {
    if (gap != gaps.end() && gap->row == i) {
      const double t0 = table.columns[time_column][i - 1];
      const double t1 = table.columns[time_column][i];
      for (std::size_t k = 1; k <= gap->missing; ++k) {
        // Linear interpolation between the samples either side of the gap, at time
        // t0 + k (t1 - t0) / (missing + 1).
        const double fraction = static_cast<double>(k) / static_cast<double>(gap->missing + 1);
        for (std::size_t c = 0; c < columns.size(); ++c) {
          const double before = table.columns[c][i - 1];
          const double after = table.columns[c][i];
          columns[c].push_back(c == time_column ? t0 + fraction * (t1 - t0) : before + fraction * (after - before));
        }
        if (lines) row_lines.push_back(0);
      }
      ++gap;
    }
    for (std::size_t c = 0; c < columns.size(); ++c) columns[c].push_back(table.columns[c][i]);
    if (lines) row_lines.push_back(table.row_lines[i]);
  }
  table.columns = std::move(columns);
  if (lines) table.row_lines = std::move(row_lines);
}

// "'time'", or the 1-based column in the file when the record has no header.
std::string column_name(const TextTable& table, std::size_t column) {
  if (column < table.names.size() && !table.names[column].empty()) return "'" + table.names[column] + "'";
  return std::to_string((column < table.fields.size() ? table.fields[column] : column) + 1);
}

TimeSegment segment(const TextTable& table, std::size_t begin, std::size_t end) {
  return {begin, end, line_of(table, begin), line_of(table, end - 1)};
}

// Stamps rounded coarser than their interval d (800 Hz to 1 ms, 0.8 Hz to 1 s, 400 Hz to 1 ms): every
// step up to 2.5 medians is one of two values a quantum q apart, floor(d/q)q and the next (1 and 2 ms,
// 2 and 3 ms), and the stamps stay within 2q of the line of equal steps d along each run between longer
// steps (the rounding moves a stamp by less than q, the line's slope by q over the run). d is then the
// mean of those steps. Fine stamps with lost samples (steps of T and 2T) drift from that line by a whole
// interval at each loss, and a record whose rate changes runs away from it: neither is recognised, nor a
// record with fewer than 20 longer steps, too few to tell rounding from loss.
struct CoarseStamps {
  double interval = 0.0;
  double quantum = 0.0;
};
std::optional<CoarseStamps> coarse_stamps(std::span<const double> time, double median) {
  const double largest = std::max(std::abs(time.front()), std::abs(time.back()));
  const double tolerance = 4.0 * (std::nextafter(largest, std::numeric_limits<double>::infinity()) - largest);
  const auto is_step = [&](std::size_t i) { return time[i] - time[i - 1] <= 2.5 * median; };
  double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
  for (std::size_t i = 1; i < time.size(); ++i) {
    if (!is_step(i)) continue;
    shortest = std::min(shortest, time[i] - time[i - 1]);
    longest = std::max(longest, time[i] - time[i - 1]);
  }
  const double quantum = longest - shortest;
  if (!(quantum > tolerance)) return std::nullopt;  // one step: fine stamps
  double sum = 0.0;
  std::size_t steps = 0, longer = 0;
  for (std::size_t i = 1; i < time.size(); ++i) {
    if (!is_step(i)) continue;
    const double step = time[i] - time[i - 1];
    const bool is_longer = std::abs(step - longest) <= tolerance;
    if (!is_longer && std::abs(step - shortest) > tolerance) return std::nullopt;  // a third value
    sum += step;
    ++steps;
    if (is_longer) ++longer;
  }
  constexpr std::size_t kFewestLonger = 20;
  if (longer < kFewestLonger) return std::nullopt;
  const double interval = sum / static_cast<double>(steps);
  for (std::size_t start = 0; start + 1 < time.size();) {
    double low = 0.0, high = 0.0;
    std::size_t i = start + 1;
    for (; i < time.size() && is_step(i); ++i) {
      const double off_line = time[i] - time[start] - static_cast<double>(i - start) * interval;
      low = std::min(low, off_line);
      high = std::max(high, off_line);
    }
    if (high - low > 2.0 * quantum + tolerance) return std::nullopt;
    start = i;
  }
  return CoarseStamps{interval, quantum};
}

// The sample interval of increasing time stamps: the mean step between gaps (a step longer than 2.5
// median steps: samples lost), so that stamps rounded coarser than the interval (400 Hz to 1 ms: steps
// of 2 and 3 ms) give it as well as fine ones, and one lost sample changes it by a step in the rows.
double interval_between_gaps(std::span<const double> time) {
  const double median = median_step(time);
  double sum = 0.0;
  std::size_t steps = 0;
  for (std::size_t i = 1; i < time.size(); ++i) {
    if (const double step = time[i] - time[i - 1]; step <= 2.5 * median) sum += step, ++steps;
  }
  return sum / static_cast<double>(steps);
}

// Seconds per unit of a time column named `name` (see RecordTimeColumn): 1 for "time" and
// "timestamp", the unit's for "time_ms", "t [us]", "Time (s)"...; nullopt for any other name.
std::optional<double> seconds_per_unit_of_time_name(const std::string& name, bool& unit_stated) {
  std::size_t letters = 0;
  while (letters < name.size() && std::isalpha(static_cast<unsigned char>(name[letters])) != 0) ++letters;
  std::string base = name.substr(0, letters);
  std::transform(base.begin(), base.end(), base.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (base != "time" && base != "t" && base != "timestamp") return std::nullopt;
  std::string_view unit = std::string_view(name).substr(letters);
  const auto is_wrapping = [](char c) { return c == ' ' || c == '_' || c == '/' || c == '(' || c == '[' || c == ')' || c == ']'; };
  while (!unit.empty() && is_wrapping(unit.front())) unit.remove_prefix(1);
  while (!unit.empty() && is_wrapping(unit.back())) unit.remove_suffix(1);
  unit_stated = !unit.empty();
  if (!unit_stated) return base == "t" ? std::nullopt : std::optional<double>(1.0);
  try {
    const Unit parsed = Unit::parse(unit);
    Dimension time;
    time.half_powers[Dimension::kTime] = 2;
    if (parsed.dimension() == time) return parsed.factor();
  } catch (const Error&) {
  }
  return std::nullopt;  // "T_degC", "t_x": a temperature, some other quantity
}

// The last stamp of column `name` of a record longer than its head: the last 64 KiB parsed under
// the head's header lines (their first, partial line dropped); nullopt where that does not parse.
std::optional<double> last_stamp(const std::string& path, const std::string& head, const TextTableHeader& header,
                                 const std::string& name) {
  std::size_t header_end = std::string::npos;  // the end of the header's line, the head's line header.line
  for (std::size_t line = 0, from = 0; line < header.line; ++line, from = header_end + 1) {
    header_end = head.find('\n', from);
    if (header_end == std::string::npos) return std::nullopt;
  }
  if (header_end == std::string::npos) return std::nullopt;  // no header line: no name to find the column by
  constexpr std::streamoff kTail = 64 << 10;
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = file.tellg();
  file.seekg(std::max<std::streamoff>(0, size - kTail));
  std::string tail(static_cast<std::size_t>(std::min(size, kTail)), '\0');
  file.read(tail.data(), static_cast<std::streamsize>(tail.size()));
  const std::size_t first_whole = tail.find('\n');
  if (first_whole == std::string::npos) return std::nullopt;
  TextTableOptions options;
  options.columns = {ColumnSelector{name, 0}};
  options.threads = 1;
  try {
    const std::vector<double> stamps =
        parse_text_table(head.substr(0, header_end + 1) + tail.substr(first_whole + 1), path, options).columns.front();
    if (!stamps.empty()) return stamps.back();
  } catch (const Error&) {
  }
  return std::nullopt;
}

}  // namespace

double seconds_per_time_stamp(const std::string& name, const std::string& stored_unit) {
  Dimension time;
  time.half_powers[Dimension::kTime] = 2;
  if (!stored_unit.empty()) {
    try {
      if (const Unit unit = Unit::parse(stored_unit); unit.dimension() == time) return unit.factor();
    } catch (const Error&) {
      // a unit inertest does not know: the name may say
    }
  }
  bool unit_stated = false;
  std::optional<double> seconds = seconds_per_unit_of_time_name(name, unit_stated);
  if (!seconds && !unit_stated && name.find_last_of("/.") != std::string::npos) {
    // A channel's own name: the last part of a group's path ("imu/time_ms") or a struct's field
    // (a header "time/ms" states its unit, above).
    seconds = seconds_per_unit_of_time_name(name.substr(name.find_last_of("/.") + 1), unit_stated);
  }
  if (seconds && unit_stated) return *seconds;
  if (unit_stated) {
    throw Error(fmt::format("the time column '{}' states a unit that is not a time (s, ms, us, ns, min, h): give "
                            "the time column (--time-column / time_column)",
                            name));
  }
  return 1.0;
}

std::vector<double> take_time_column_s(TextTable& table, std::size_t column) {
  require_increasing_time(table, column);
  double seconds = 1.0;
  try {
    seconds = seconds_per_time_stamp(column < table.names.size() ? table.names[column] : "");
  } catch (const Error& e) {
    throw Error(SourceLocation{table.source, table.header_line, 0}, e.message());
  }
  std::vector<double> time = std::move(table.columns.at(column));
  if (seconds != 1.0) {
    for (double& stamp : time) stamp *= seconds;
  }
  return time;
}

std::optional<RecordHead> read_record_head(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return std::nullopt;  // a pipe is not read ahead
  constexpr std::size_t kHead = std::size_t{256} << 10;
  RecordHead head;
  head.text.assign(kHead, '\0');
  std::ifstream file(path, std::ios::binary);
  file.read(head.text.data(), static_cast<std::streamsize>(kHead));
  head.text.resize(static_cast<std::size_t>(file.gcount()));
  head.whole = head.text.size() < kHead;
  if (!head.whole) head.text.resize(head.text.rfind('\n') == std::string::npos ? 0 : head.text.rfind('\n') + 1);
  try {
    head.header = parse_text_table_header(head.text, path);
  } catch (const Error&) {
    return std::nullopt;  // text the record's reader refuses with its own message, or a binary record
  }
  return head;
}

double RecordTimeColumn::sample_rate_hz() const {
  return std::stod(fmt::format("{:.12g}", 1.0 / sample_interval_s));
}

std::optional<RecordTimeColumn> find_record_time_column(const std::string& path) {
  const std::optional<RecordHead> read = read_record_head(path);
  if (!read) return std::nullopt;
  const std::string& head = read->text;
  const TextTableHeader& header = read->header;
  const bool whole = read->whole;
  for (const std::string& name : header.names) {
    bool unit_stated = false;
    const std::optional<double> seconds = seconds_per_unit_of_time_name(name, unit_stated);
    if (!seconds) continue;
    TextTableOptions options;
    options.columns = {ColumnSelector{name, 0}};
    options.threads = 1;
    std::vector<double> time;
    try {
      time = std::move(parse_text_table(head, path, options).columns.front());
    } catch (const Error&) {
      continue;  // text stamps (an ISO date), a bad cell: another column may be the time
    }
    if (time.size() < 3 || std::adjacent_find(time.begin(), time.end(), std::greater_equal<>()) != time.end()) continue;
    const std::optional<double> last = whole ? std::optional(time.back()) : last_stamp(path, head, header, name);
    return RecordTimeColumn{name, SourceLocation{path, header.line, 0}, unit_stated,
                            *seconds * interval_between_gaps(time), time.size(), *seconds * time.front(),
                            *seconds * last.value_or(std::numeric_limits<double>::quiet_NaN())};
  }
  return std::nullopt;
}

void check_sample_rate_against_time_column(const std::string& path, double sample_rate_hz) {
  const std::optional<RecordTimeColumn> time = find_record_time_column(path);
  // A name without its unit may hold ticks, ns or anything: only a stated unit is held against.
  if (!(sample_rate_hz > 0.0) || !time || !time->unit_stated) return;
  // Within 5 %: the mistakes this finds are factors (10 Hz taken as 100 Hz, ms taken as s), not a
  // cheap oscillator's few percent.
  if (std::abs(time->sample_interval_s * sample_rate_hz - 1.0) <= 0.05) return;
  throw Error(time->header,
              fmt::format("sample_rate_hz (--rate) {:g} Hz contradicts the record's time column '{}': its first {} "
                          "stamps step {:.6g} s ({:.6g} Hz); give the rate the record was logged at (or, if '{}' is "
                          "no time in the unit its name says, rename it)",
                          sample_rate_hz, time->name, time->rows, time->sample_interval_s, 1.0 / time->sample_interval_s,
                          time->name));
}

void check_time_column_span(const std::string& path, std::size_t rows) {
  const std::optional<RecordTimeColumn> time = find_record_time_column(path);
  if (rows < 2 || !time || !time->unit_stated || !(time->last_s > time->first_s)) return;
  const double span = time->last_s - time->first_s;
  const double expected = static_cast<double>(rows - 1) * time->sample_interval_s;
  if (std::abs(span - expected) <= 3.0 * time->sample_interval_s + 2e-4 * expected) return;
  throw Error(time->header,
              fmt::format("the time column '{}' spans {:.6g} s from the first sample to the last, but its {} samples "
                          "at the interval of its first rows ({:.6g} s) span {:.6g} s: samples are missing (a gap) or "
                          "the rate changes within the record (`inertest inspect {} --time-column '{}'` lists the gaps)",
                          time->name, span, rows, time->sample_interval_s, expected, path, time->name));
}

GapPolicy parse_gap_policy(std::string_view text) {
  if (text == "stop") return GapPolicy::kStop;
  if (text == "split") return GapPolicy::kSplit;
  if (text == "interpolate") return GapPolicy::kInterpolate;
  throw Error("unknown gap policy '" + std::string(text) + "' (expected stop, split or interpolate)");
}

std::string to_string(GapPolicy policy) {
  switch (policy) {
    case GapPolicy::kStop: return "stop";
    case GapPolicy::kSplit: return "split";
    case GapPolicy::kInterpolate: return "interpolate";
  }
  return "stop";
}

void TimeStampOptions::validate() const {
  if (sample_interval && !(std::isfinite(*sample_interval) && *sample_interval > 0.0)) {
    throw Error(fmt::format("the sample interval must be positive, not {:g}", *sample_interval));
  }
  if (!(std::isfinite(gap_factor) && gap_factor > 1.0)) {
    throw Error(fmt::format("the gap factor must exceed 1 sample interval, not {:g}", gap_factor));
  }
}

TimeGaps find_time_gaps(std::span<const double> time, std::span<const std::size_t> lines,
                        const TimeStampOptions& options) {
  TimeGaps found;
  const double median = median_step(time);
  const std::optional<CoarseStamps> coarse = options.sample_interval ? std::nullopt : coarse_stamps(time, median);
  const double nominal = options.sample_interval.value_or(coarse ? coarse->interval : median);
  // A coarse stamp is off by up to one quantum: a gap is a step longer than the interval by more than
  // that, so that a step to the next quantum is none.
  const double factor = coarse ? std::max(options.gap_factor, 1.0 + coarse->quantum / nominal) : options.gap_factor;
  std::vector<std::size_t> gap_rows;
  for (std::size_t i = 1; i < time.size(); ++i) {
    if ((time[i] - time[i - 1]) / nominal > factor) gap_rows.push_back(i);
  }
  found.stamp_quantum = coarse ? coarse->quantum : 0.0;
  found.sample_interval = options.sample_interval || coarse ? nominal : refined_step(time, gap_rows, nominal);
  for (std::size_t i : gap_rows) {
    const double ratio = (time[i] - time[i - 1]) / found.sample_interval;
    found.gaps.push_back({i, i < lines.size() ? lines[i] : 0, time[i - 1], time[i], missing_samples(ratio)});
  }
  return found;
}

TimeStampReport check_time_stamps(TextTable& table, std::size_t time_column, const TimeStampOptions& options) {
  options.validate();
  if (time_column >= table.columns.size()) {
    throw Error(SourceLocation{table.source, 0, 0}, "time column " + std::to_string(time_column + 1) + " was not read");
  }
  const std::vector<double>& time = table.columns[time_column];
  const std::string name = column_name(table, time_column);
  if (time.size() < 2) {
    throw Error(locate_cell(table, 0, time_column),
                fmt::format("time column {} has {} sample(s); a sample interval needs at least 2", name, time.size()));
  }
  for (std::size_t i = 1; i < time.size(); ++i) {
    if (time[i] > time[i - 1]) continue;
    const std::string previous = line_of(table, i - 1) > 0 ? fmt::format(" at line {}", line_of(table, i - 1)) : "";
    throw Error(locate_cell(table, i, time_column),
                time[i] == time[i - 1]
                    ? fmt::format("time stamp {:.10g} repeats the one before it{} (time column {})", time[i], previous, name)
                    : fmt::format("time goes backwards: {:.10g} after {:.10g}{} (time column {})", time[i], time[i - 1],
                                  previous, name));
  }

  TimeStampReport report;
  report.policy = options.policy;
  TimeGaps found = find_time_gaps(time, table.row_lines, options);
  report.sample_interval = found.sample_interval;
  report.gaps = std::move(found.gaps);
  if (options.policy == GapPolicy::kStop && !report.gaps.empty()) {
    const TimeGap& gap = report.gaps.front();
    throw Error(locate_cell(table, gap.row, time_column),
                fmt::format("gap in the time stamps: {:.10g} to {:.10g} is {:.4g} sample intervals of {:.6g}, {} "
                            "sample(s) missing (time column {}; the gap policy 'split' or 'interpolate' accepts it)",
                            gap.time_before, gap.time_after, (gap.time_after - gap.time_before) / report.sample_interval,
                            report.sample_interval, gap.missing, name));
  }

  if (options.policy == GapPolicy::kInterpolate && !report.gaps.empty()) {
    for (const auto& gap : report.gaps) report.interpolated_samples += gap.missing;
    if (report.interpolated_samples > time.size()) {
      const TimeGap& longest = *std::max_element(report.gaps.begin(), report.gaps.end(),
                                                 [](const auto& a, const auto& b) { return a.missing < b.missing; });
      throw Error(locate_cell(table, longest.row, time_column),
                  fmt::format("interpolation would add {} samples to a record of {}: the gaps are too long to fill "
                              "(the longest, {} samples, ends here); split the record instead",
                              report.interpolated_samples, time.size(), longest.missing));
    }
    interpolate_gaps(table, report.gaps, time_column);
  }

  if (options.policy == GapPolicy::kSplit) {
    std::size_t begin = 0;
    for (const auto& gap : report.gaps) {
      report.segments.push_back(segment(table, begin, gap.row));
      begin = gap.row;
    }
    report.segments.push_back(segment(table, begin, table.rows()));
  } else {
    report.segments.push_back(segment(table, 0, table.rows()));
  }
  return report;
}

nlohmann::json TimeStampReport::to_json() const {
  nlohmann::json gap_list = nlohmann::json::array();
  for (const auto& gap : gaps) {
    gap_list.push_back({{"line", gap.line}, {"time_before", gap.time_before}, {"time_after", gap.time_after},
                        {"missing_samples", gap.missing}});
  }
  nlohmann::json segment_list = nlohmann::json::array();
  for (const auto& s : segments) {
    segment_list.push_back({{"first_line", s.first_line}, {"last_line", s.last_line}, {"samples", s.size()}});
  }
  return {{"gap_policy", to_string(policy)}, {"sample_interval", sample_interval},   {"gaps", gap_list},
          {"segments", segment_list},        {"interpolated_samples", interpolated_samples}};
}

}  // namespace inertest

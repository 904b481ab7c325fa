#include "inertest/io/time_stamps.h"

#include <cmath>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;

// time,gyro at 10 ms with samples 0.03 and 0.04 missing (a gap of 3 intervals after line 4), and
// gyro = 100 t + 1 so that interpolated values are known exactly.
constexpr const char* kGap = "time,gyro\n0.00,1\n0.01,2\n0.02,3\n0.05,6\n0.06,7\n";

TextTable table_of(const std::string& text) { return parse_text_table(text, "rec.csv"); }

std::string error_of(const std::string& text, TimeStampOptions options = {}) {
  TextTable table = table_of(text);
  try {
    check_time_stamps(table, 0, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(TimeStamps, RegularRecordIsOneSegment) {
  TextTable table = table_of("t,v\n0,1\n0.5,2\n1.0,3\n1.5,4\n");
  const TimeStampReport report = check_time_stamps(table, 0, {});
  EXPECT_DOUBLE_EQ(report.sample_interval, 0.5);
  EXPECT_TRUE(report.gaps.empty());
  ASSERT_EQ(report.segments.size(), 1u);
  EXPECT_EQ(report.segments[0].size(), 4u);
  EXPECT_EQ(report.segments[0].first_line, 2u);
  EXPECT_EQ(report.segments[0].last_line, 5u);
}

// Epoch seconds (1.7e9) at 1 kHz, written to the millisecond: doubles there are 2.4e-7 s apart and
// the median step read 0.99992752 ms (72 ppm; a gap of 1e5 intervals miscounted by 7). The mean
// step between the gaps gives the interval to within two roundings a run over the steps (0.17 ppm
// here); a gap of 100 samples is counted exactly.
TEST(TimeStamps, CoarseEpochStampsGiveTheIntervalAndTheMissingCount) {
  std::string text = "time,gyro\n";
  for (int i = 0; i < 3000; ++i) {
    if (i >= 1000 && i < 1100) continue;  // 100 samples missing
    text += fmt::format("{:.3f},{}\n", 1.7e9 + i / 1000.0, i);
  }
  TextTable table = table_of(text);
  TimeStampOptions options;
  options.policy = GapPolicy::kSplit;
  const TimeStampReport report = check_time_stamps(table, 0, options);
  // Two runs, each end rounded by at most half the spacing 2^-22 s: 4 x 2^-23 s over 2899 steps.
  EXPECT_NEAR(report.sample_interval, 1e-3, 4.0 * std::ldexp(1.0, -23) / 2899.0);
  ASSERT_EQ(report.gaps.size(), 1u);
  EXPECT_EQ(report.gaps[0].missing, 100u);
}

// Stamps rounded coarser than the interval: 800 Hz written to the millisecond steps 1 and 2 ms, 0.8 Hz
// written to the second 1 and 2 s. Neither long step is a gap (each was one, and a whole record was
// refused); the interval is the mean step, and samples lost are still found: 2 at 800 Hz (a step of 3 or
// 4 ms), and 1680 at 0.8 Hz, counted to within the rounding of the stamps either side (a sample).
TEST(TimeStamps, StampsCoarserThanTheIntervalAreNoGaps) {
  const auto record = [](double rate, double quantum, int n, int lost_from, int lost) {
    std::string text = "time,gyro\n";
    for (int i = 0; i < n; ++i) {
      if (i >= lost_from && i < lost_from + lost) continue;
      text += fmt::format("{:.6g},{}\n", std::floor(i / rate / quantum) * quantum, i);
    }
    return text;
  };
  TextTable whole = table_of(record(800.0, 1e-3, 8000, 0, 0));
  const TimeStampReport report = check_time_stamps(whole, 0, {});
  EXPECT_TRUE(report.gaps.empty());
  EXPECT_NEAR(report.sample_interval, 1.25e-3, 1e-3 / 7999.0);
  EXPECT_THAT(error_of(record(800.0, 1e-3, 8000, 4000, 2)),
              HasSubstr("rec.csv:4002: gap in the time stamps: 4.998 to "));
  TimeStampOptions split;
  split.policy = GapPolicy::kSplit;
  TextTable slow = table_of(record(0.8, 1.0, 16800, 8000, 1680));
  const TimeStampReport outage = check_time_stamps(slow, 0, split);
  ASSERT_EQ(outage.gaps.size(), 1u);
  EXPECT_NEAR(static_cast<double>(outage.gaps[0].missing), 1680.0, 1.0);
  EXPECT_NEAR(outage.sample_interval, 1.25, 2.0 / 15118.0);
  // 400 Hz in ms steps 2 and 3 ms: the interval is 2.5 ms (it was 2, and an outage of 100 samples 125).
  TextTable four_hundred = table_of(record(400.0, 1e-3, 20000, 10000, 100));
  const TimeStampReport quarter = check_time_stamps(four_hundred, 0, split);
  EXPECT_NEAR(quarter.sample_interval, 2.5e-3, 1e-3 / 9999.0);
  ASSERT_EQ(quarter.gaps.size(), 1u);
  EXPECT_EQ(quarter.gaps[0].missing, 100u);
}

// What is not rounding: fine stamps that lose 6 % of their samples one at a time (steps of T and 2T, as
// rounded stamps have, but drifting a whole interval from the line at each loss), a record whose rate
// changes (100 Hz, then 50 Hz), and a short record with one lost sample. Each long step stays a gap.
TEST(TimeStamps, LostSamplesAndAChangeOfRateAreNoCoarseStamps) {
  testing::UniformSequence uniform(3);
  std::string lost = "time,gyro\n";
  std::size_t kept = 0;
  for (int i = 0; i < 20000; ++i) {
    if (i > 0 && uniform.next() + 0.5 < 0.06) continue;  // 6 % of the samples
    lost += fmt::format("{:.3f},{}\n", i / 1000.0, i);
    ++kept;
  }
  TimeStampOptions split;
  split.policy = GapPolicy::kSplit;
  TextTable fine = table_of(lost);
  const TimeStampReport losses = check_time_stamps(fine, 0, split);
  EXPECT_NEAR(losses.sample_interval, 1e-3, 1e-12);
  std::size_t missing = 0;
  for (const TimeGap& gap : losses.gaps) missing += gap.missing;
  EXPECT_EQ(missing + kept, 20000u);
  std::string changing = "time,gyro\n";
  for (int i = 0; i < 5000; ++i) changing += fmt::format("{:.2f},0\n", i / 100.0);
  for (int i = 0; i < 5000; ++i) changing += fmt::format("{:.2f},0\n", 50.0 + i / 50.0);
  EXPECT_THAT(error_of(changing), HasSubstr("gap in the time stamps"));
  EXPECT_THAT(error_of("time,gyro\n0,1\n1,2\n3,3\n"), HasSubstr("rec.csv:4: gap in the time stamps"));
}

// Steps that truly vary (0.9, 1.1, ...) keep the median step (the lower: 0.9): the mean is no
// rounding of it.
TEST(TimeStamps, VaryingStepsKeepTheMedian) {
  TextTable table = table_of("t,v\n0,1\n0.9,2\n2.0,3\n2.9,4\n4.0,5\n");
  EXPECT_DOUBLE_EQ(check_time_stamps(table, 0, {}).sample_interval, 0.9);
}

TEST(TimeStamps, StopNamesTheGap) {
  EXPECT_THAT(error_of(kGap), HasSubstr("rec.csv:5: gap in the time stamps: 0.02 to 0.05 is 3 sample intervals of "
                                        "0.01, 2 sample(s) missing (time column 'time'"));
}

TEST(TimeStamps, SplitReturnsTheContiguousSegments) {
  TextTable table = table_of(kGap);
  TimeStampOptions options;
  options.policy = GapPolicy::kSplit;
  const TimeStampReport report = check_time_stamps(table, 0, options);
  ASSERT_EQ(report.gaps.size(), 1u);
  EXPECT_EQ(report.gaps[0].row, 3u);
  EXPECT_EQ(report.gaps[0].line, 5u);
  EXPECT_EQ(report.gaps[0].missing, 2u);
  EXPECT_DOUBLE_EQ(report.gaps[0].time_before, 0.02);
  EXPECT_DOUBLE_EQ(report.gaps[0].time_after, 0.05);
  ASSERT_EQ(report.segments.size(), 2u);
  EXPECT_EQ(report.segments[0].begin, 0u);
  EXPECT_EQ(report.segments[0].end, 3u);
  EXPECT_EQ(report.segments[1].begin, 3u);
  EXPECT_EQ(report.segments[1].end, 5u);
  EXPECT_EQ(report.segments[1].first_line, 5u);
  EXPECT_EQ(report.segments[1].last_line, 6u);
  EXPECT_EQ(table.rows(), 5u);  // split leaves the table as read
  EXPECT_EQ(report.to_json()["segments"][1]["samples"], 2);
}

TEST(TimeStamps, InterpolateFillsTheMissingSamplesLinearly) {
  TextTable table = table_of(kGap);
  TimeStampOptions options;
  options.policy = GapPolicy::kInterpolate;
  const TimeStampReport report = check_time_stamps(table, 0, options);
  EXPECT_EQ(report.interpolated_samples, 2u);
  ASSERT_EQ(table.rows(), 7u);
  const std::vector<double> time{0.00, 0.01, 0.02, 0.03, 0.04, 0.05, 0.06};
  for (std::size_t i = 0; i < time.size(); ++i) {
    EXPECT_NEAR(table.columns[0][i], time[i], 1e-15) << i;
    EXPECT_NEAR(table.columns[1][i], 100.0 * time[i] + 1.0, 1e-12) << i;  // gyro = 100 t + 1
  }
  EXPECT_EQ(table.row_lines, (std::vector<std::size_t>{2, 3, 4, 0, 0, 5, 6}));
  ASSERT_EQ(report.segments.size(), 1u);
  EXPECT_EQ(report.segments[0].size(), 7u);
}

TEST(TimeStamps, GivenIntervalAndFactor) {
  // At a nominal 20 ms the 30 ms step is no gap (1.5 intervals is not more than 1.5).
  TextTable table = table_of("t,v\n0,1\n0.02,1\n0.05,1\n0.07,1\n");
  TimeStampOptions options;
  options.sample_interval = 0.02;
  EXPECT_TRUE(check_time_stamps(table, 0, options).gaps.empty());
  options.gap_factor = 1.2;
  options.policy = GapPolicy::kSplit;
  EXPECT_EQ(check_time_stamps(table, 0, options).gaps.size(), 1u);
  options.gap_factor = 1.0;
  EXPECT_THROW(check_time_stamps(table, 0, options), Error);
}

TEST(TimeStamps, BackwardsRepeatsAndTooFew) {
  EXPECT_THAT(error_of("t,v\n0,1\n1,1\n0.5,1\n"), HasSubstr("rec.csv:4: time goes backwards: 0.5 after 1 at line 3"));
  EXPECT_THAT(error_of("t,v\n0,1\n1,1\n1,1\n"), HasSubstr("rec.csv:4: time stamp 1 repeats the one before it at line 3"));
  EXPECT_THAT(error_of("t,v\n0,1\n"), HasSubstr("rec.csv:2: time column 't' has 1 sample(s)"));
}

TEST(TimeStamps, RefusesToInventMostOfARecord) {
  TimeStampOptions options;
  options.policy = GapPolicy::kInterpolate;
  EXPECT_THAT(error_of("t,v\n0,1\n1,1\n2,1\n1e300,1\n", options),
              HasSubstr("rec.csv:5: interpolation would add 1000000000000000 samples to a record of 4"));
  options.policy = GapPolicy::kSplit;
  EXPECT_EQ(error_of("t,v\n0,1\n1,1\n2,1\n1e300,1\n", options), "no error");
}

// A record's time column by its header name: the unit the name states, or s; none for "t" alone
// or a temperature ("T_degC").
struct TimeColumnCase {
  const char* name;
  double stamp_step;       // in the column's own unit
  double interval_s;       // what find_record_time_column gives; 0: no time column
  bool unit_stated;
};

class RecordTimeColumnTest : public ::testing::TestWithParam<TimeColumnCase> {};

TEST_P(RecordTimeColumnTest, IsFoundByItsName) {
  const TimeColumnCase& c = GetParam();
  testing::ScratchDirectory dir;
  std::string text = fmt::format("{},gyro\n", c.name);
  for (int i = 0; i < 50; ++i) text += fmt::format("{},{}\n", 1000.0 + i * c.stamp_step, i % 3);
  const std::optional<RecordTimeColumn> found = find_record_time_column(dir.write("r.csv", text));
  if (c.interval_s == 0.0) {
    EXPECT_FALSE(found.has_value());
    return;
  }
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->name, c.name);
  EXPECT_EQ(found->header.line, 1u);
  EXPECT_EQ(found->rows, 50u);
  EXPECT_EQ(found->unit_stated, c.unit_stated);
  EXPECT_NEAR(found->sample_interval_s, c.interval_s, 1e-12 * c.interval_s);
}

INSTANTIATE_TEST_SUITE_P(Names, RecordTimeColumnTest,
                         ::testing::Values(TimeColumnCase{"time", 0.01, 0.01, false},
                                           TimeColumnCase{"Timestamp", 0.5, 0.5, false},
                                           TimeColumnCase{"time_s", 0.01, 0.01, true},
                                           TimeColumnCase{"t_ms", 10.0, 0.01, true},
                                           TimeColumnCase{"Time (s)", 0.25, 0.25, true},
                                           TimeColumnCase{"time [us]", 1000.0, 0.001, true},
                                           TimeColumnCase{"time/min", 1.0, 60.0, true},
                                           TimeColumnCase{"t", 0.01, 0.0, false},
                                           TimeColumnCase{"T_degC", 0.01, 0.0, false},
                                           TimeColumnCase{"time_V", 0.01, 0.0, false},
                                           TimeColumnCase{"timer", 0.01, 0.0, false}));

TEST(RecordTimeColumn, CoarseStampsGapsAndWhatIsNoTimeColumn) {
  testing::ScratchDirectory dir;
  // 400 Hz stamped to 1 ms: steps of 2 and 3 ms (the median 2 ms), the interval 2.5 ms.
  std::string coarse = "time_s,gyro\n";
  for (int i = 0; i < 401; ++i) coarse += fmt::format("{:.3f},1\n", i / 400.0);
  const std::string stamped = dir.write("coarse.csv", coarse);
  const std::optional<RecordTimeColumn> found = find_record_time_column(stamped);
  ASSERT_TRUE(found.has_value());
  EXPECT_NEAR(found->sample_interval_s, 0.0025, 1e-12);
  EXPECT_NO_THROW(check_sample_rate_against_time_column(stamped, 400.0));
  EXPECT_THROW(check_sample_rate_against_time_column(stamped, 500.0), Error);
  EXPECT_THROW(check_sample_rate_against_time_column(stamped, 333.0), Error);
  // A gap of 10 missing samples is left out of the interval.
  std::string gap = "time_s,gyro\n";
  for (int i = 0; i < 100; ++i) gap += fmt::format("{:.2f},1\n", (i < 50 ? i : i + 10) / 100.0);
  const std::optional<RecordTimeColumn> gapped = find_record_time_column(dir.write("gap.csv", gap));
  ASSERT_TRUE(gapped.has_value());
  EXPECT_NEAR(gapped->sample_interval_s, 0.01, 1e-12);
  // Stamps that do not increase, too few, no header, a bad cell: no time column, and the record's
  // reader gives its own errors. A column of text beside, or before the time, is passed over.
  EXPECT_FALSE(find_record_time_column(dir.write("back.csv", "time,g\n0,1\n2,1\n1,1\n3,1\n")));
  EXPECT_FALSE(find_record_time_column(dir.write("two.csv", "time,g\n0,1\n1,1\n")));
  EXPECT_FALSE(find_record_time_column(dir.write("bare.csv", "0,1\n1,1\n2,1\n3,1\n")));
  EXPECT_FALSE(find_record_time_column(dir.write("bad.csv", "time,g\n0,1\nx,1\n2,1\n3,1\n")));
  EXPECT_TRUE(find_record_time_column(dir.write("text.csv", "time,g,note\n0,1,a\n1,1,b\n2,1,c\n")));
  const std::optional<RecordTimeColumn> second = find_record_time_column(
      dir.write("iso.csv", "timestamp,time_s,g\n2026-11-27T03:00:00,0,1\n2026-11-27T03:00:01,1,1\n2026-11-27T03:00:02,2,1\n"));
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->name, "time_s");
  EXPECT_FALSE(find_record_time_column(dir.path() + "/missing.csv"));
}

TEST(RecordTimeColumn, ARateItContradictsIsAnError) {
  testing::ScratchDirectory dir;
  std::string text = "time_s,gyro\n";
  for (int i = 0; i < 100; ++i) text += fmt::format("{:.1f},1\n", i / 10.0);
  const std::string path = dir.write("r.csv", text);
  EXPECT_NO_THROW(check_sample_rate_against_time_column(path, 10.0));
  EXPECT_NO_THROW(check_sample_rate_against_time_column(path, 10.49));  // within 5 %
  EXPECT_THROW(check_sample_rate_against_time_column(path, 10.6), Error);
  try {
    check_sample_rate_against_time_column(path, 100.0);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("r.csv:1: sample_rate_hz (--rate) 100 Hz contradicts the record's time column "
                                    "'time_s': its first 100 stamps step 0.1 s (10 Hz); give the rate the record was "
                                    "logged at"));
  }
  // Stamps in ms by their name.
  const std::string ms = dir.write("ms.csv", "t_ms,gyro\n0,1\n100,1\n200,1\n300,1\n");
  EXPECT_NO_THROW(check_sample_rate_against_time_column(ms, 10.0));
  EXPECT_THROW(check_sample_rate_against_time_column(ms, 100.0), Error);
  // A name that states no unit may hold ticks: never held against the rate.
  const std::string ticks = dir.write("ticks.csv", "time,gyro\n0,1\n1,1\n2,1\n3,1\n");
  EXPECT_NO_THROW(check_sample_rate_against_time_column(ticks, 100.0));
  EXPECT_NO_THROW(check_sample_rate_against_time_column(dir.write("none.csv", "gyro\n1\n2\n3\n"), 100.0));
}

// The whole record's span against its rows at the column's own interval: a gap or a change of rate
// past the head (read from the file's end, under the header and a comment) is an error; a clock a
// few percent off its nominal rate, or one that wraps past midnight, is not.
TEST(RecordTimeColumn, ItsSpanMustBeItsRowsAtItsInterval) {
  testing::ScratchDirectory dir;
  const auto record = [&](const std::string& name, const std::vector<double>& stamps) {
    std::string text = "# logger export\ntime_s,gyro\n";
    for (double t : stamps) text += fmt::format("{:.3f},1\n", t);
    return dir.write(name, text);
  };
  std::vector<double> regular;  // 60000 rows at 10 Hz: longer than the 256 KiB head
  for (int i = 0; i < 60000; ++i) regular.push_back(i / 10.0);
  const std::string whole = record("whole.csv", regular);
  EXPECT_NO_THROW(check_time_column_span(whole, regular.size()));
  // Within 3 intervals and 2e-4 of the span: 1.5 s, 15 rows here.
  EXPECT_NO_THROW(check_time_column_span(whole, regular.size() - 14));
  EXPECT_THROW(check_time_column_span(whole, regular.size() - 16), Error);
  std::vector<double> gapped = regular;
  gapped.erase(gapped.begin() + 40000, gapped.begin() + 40500);  // 50 s missing past the head
  const std::string gap = record("gap.csv", gapped);
  EXPECT_NO_THROW(check_sample_rate_against_time_column(gap, 10.0));  // the head is regular
  try {
    check_time_column_span(gap, gapped.size());
    ADD_FAILURE() << "the gap went unsaid";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("gap.csv:2: the time column 'time_s' spans 5999.9 s from the first sample to the "
                                    "last, but its 59500 samples at the interval of its first rows (0.1 s) span "
                                    "5949.9 s: samples are missing (a gap) or the rate changes within the record"));
  }
  std::vector<double> slower = regular;  // from 4000 s on at 1 Hz
  for (std::size_t i = 40000; i < slower.size(); ++i) slower[i] = 4000.0 + static_cast<double>(i - 40000);
  EXPECT_THROW(check_time_column_span(record("slower.csv", slower), slower.size()), Error);
  // A clock 3 % slow (stamps every 10.3 ms of a nominal 100 Hz): its own interval, no gap.
  std::vector<double> drifting;
  for (int i = 0; i < 40000; ++i) drifting.push_back(i * 0.0103);
  EXPECT_NO_THROW(check_time_column_span(record("drift.csv", drifting), drifting.size()));
  // Seconds of the day past midnight (after the head): not held to the span.
  std::vector<double> midnight;
  for (int i = 0; i < 60000; ++i) midnight.push_back(std::fmod(82000.0 + i / 10.0, 86400.0));
  EXPECT_NO_THROW(check_time_column_span(record("midnight.csv", midnight), midnight.size()));
  // A short record is its own head; ticks (no unit stated) and no time column are not checked.
  EXPECT_THROW(check_time_column_span(record("short.csv", {0.0, 0.1, 0.2, 0.3, 1.4, 1.5}), 6), Error);
  EXPECT_NO_THROW(check_time_column_span(dir.write("ticks.csv", "time,gyro\n0,1\n1,1\n9,1\n10,1\n"), 4));
  EXPECT_NO_THROW(check_time_column_span(dir.write("none.csv", "gyro\n1\n2\n3\n"), 3));
}

TEST(TimeStamps, ParsesThePolicy) {
  EXPECT_EQ(parse_gap_policy("split"), GapPolicy::kSplit);
  EXPECT_EQ(to_string(parse_gap_policy("interpolate")), "interpolate");
  EXPECT_THROW(parse_gap_policy("ignore"), Error);
}

// The time column of a record read by name or place: in s, converted by the unit its name states.
TEST(TimeColumnInSeconds, TheUnitItsNameStatesConvertsIt) {
  testing::ScratchDirectory scratch;
  const auto stamps_of = [&](const std::string& header, const std::string& column) {
    TextTableOptions options;
    options.columns = {ColumnSelector::parse(column), ColumnSelector::parse("2")};
    TextTable table = read_text_table(scratch.write("record.csv", header + ",output\n1000,5\n2000,6\n3500,7\n"), options);
    return take_time_column_s(table, 0);
  };
  EXPECT_EQ(stamps_of("time_ms", "time_ms"), (std::vector<double>{1.0, 2.0, 3.5}));
  EXPECT_EQ(stamps_of("t [ms]", "1"), (std::vector<double>{1.0, 2.0, 3.5}));
  EXPECT_EQ(stamps_of("Time (min)", "1"), (std::vector<double>{60000.0, 120000.0, 210000.0}));
  // No unit stated, or a name that is no time's: in s, as before.
  EXPECT_EQ(stamps_of("time", "1"), (std::vector<double>{1000.0, 2000.0, 3500.0}));
  EXPECT_EQ(stamps_of("stamp", "1"), (std::vector<double>{1000.0, 2000.0, 3500.0}));
  EXPECT_EQ(stamps_of("time_s", "1"), (std::vector<double>{1000.0, 2000.0, 3500.0}));
  for (const auto& [header, seconds] : {std::pair{"time_ns", 1e-9}, std::pair{"t [µs]", 1e-6}, std::pair{"t [μs]", 1e-6}}) {
    const std::vector<double> stamps = stamps_of(header, "1");
    ASSERT_EQ(stamps.size(), 3u);
    const std::vector<double> written = {1000.0, 2000.0, 3500.0};
    for (std::size_t i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(stamps[i], seconds * written[i]) << header;
  }
  EXPECT_EQ(stamps_of("time_msec", "1"), (std::vector<double>{1.0, 2.0, 3.5}));
  EXPECT_EQ(stamps_of("time/ms", "1"), (std::vector<double>{1.0, 2.0, 3.5}));
  // A time's name that states no time unit is an error at the header, not seconds.
  try {
    stamps_of("T_degC", "1");
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("record.csv:1: the time column 'T_degC' states a unit that is not a time"));
  }
  // A channel: the unit its file stores, else the name of its own (the last part of its path).
  EXPECT_EQ(seconds_per_time_stamp("imu/time_ms"), 1e-3);
  EXPECT_EQ(seconds_per_time_stamp("run.time_us"), 1e-6);
  EXPECT_EQ(seconds_per_time_stamp("imu/stamp", "ms"), 1e-3);
  EXPECT_EQ(seconds_per_time_stamp("time_ms", "s"), 1.0);
  EXPECT_EQ(seconds_per_time_stamp("imu/stamp"), 1.0);
  // Going back is still an error at its cell.
  TextTableOptions options;
  options.columns = {ColumnSelector::parse("1")};
  TextTable table = read_text_table(scratch.write("back.csv", "time_ms\n1\n3\n2\n"), options);
  EXPECT_THROW(take_time_column_s(table, 0), Error);
}

}  // namespace
}  // namespace inertest

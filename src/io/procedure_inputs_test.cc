#include "inertest/io/procedure_inputs.h"

#include "test_util/test_util.h"

namespace inertest {
namespace {

using testing::ScratchDirectory;
using ::testing::HasSubstr;

// The message of the Error that f throws, with its location.
template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(FileListing, ResolvesPathsAgainstTheListingsDirectory) {
  ScratchDirectory scratch;
  scratch.write("data/a.csv", "1\n");
  scratch.write("data/b.csv", "2\n");
  const auto listing = scratch.write("data/list.csv", "# runs\ntemperature_degC,note,file\n20,room,a.csv\n\n-40, cold , b.csv\n");
  const auto rows = read_file_listing(listing, "temperature_degC");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].key, 20.0);
  EXPECT_EQ(rows[1].key, -40.0);
  EXPECT_EQ(rows[1].path, scratch.path() + "/data/b.csv");
  EXPECT_EQ(rows[1].where.line, 5u);
}

// A listing saved by Excel as "CSV UTF-8" starts with a byte order mark: its header was not found.
TEST(FileListing, AByteOrderMarkIsNoPartOfTheHeader) {
  ScratchDirectory scratch;
  scratch.write("a.csv", "1\n");
  const auto rows = read_file_listing(scratch.write("list.csv", "\xEF\xBB\xBFrate,file\n5,a.csv\n"), "rate");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].key, 5.0);
  EXPECT_EQ(rows[0].where.column, 1u);
}

// Cells separated as the first line separates them: ';' (a European Excel's CSV), tabs or blanks;
// a ';' listing was refused with "expected a header row naming the columns".
TEST(FileListing, SemicolonsTabsAndBlanksSeparateCellsToo) {
  ScratchDirectory scratch;
  scratch.write("a.csv", "1\n");
  for (const char* text : {"freq_hz;file\n10;a.csv\n", "freq_hz\tfile\n10\ta.csv\n", "freq_hz   file\n10  a.csv\n"}) {
    const auto rows = read_file_listing(scratch.write("list.csv", text), "freq_hz");
    ASSERT_EQ(rows.size(), 1u) << text;
    EXPECT_EQ(rows[0].key, 10.0);
    EXPECT_EQ(rows[0].path, scratch.path() + "/a.csv");
  }
}

TEST(FileListing, QuotedFieldsHoldCommasAndBlanks) {
  ScratchDirectory scratch;
  scratch.write("run 1, cold.csv", "1\n");
  const auto listing = scratch.write("list.csv", "\"freq_hz\",\"file\"\n\"10\",\"run 1, cold.csv\"\n");
  const auto rows = read_file_listing(listing, "freq_hz");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].key, 10.0);
  EXPECT_EQ(rows[0].path, scratch.path() + "/run 1, cold.csv");
  const auto open_quote = scratch.write("o.csv", "freq_hz,file\n10,\"run 1.csv\n");
  EXPECT_THAT(error_of([&] { read_file_listing(open_quote, "freq_hz"); }),
              HasSubstr(open_quote + ":2:4: a quoted field with no closing quote"));
}

TEST(FileListing, BadListingsNameTheirPlace) {
  ScratchDirectory scratch;
  scratch.write("a.csv", "1\n");
  const auto bad_number = scratch.write("n.csv", "freq_hz,file\n10,a.csv\n1x,a.csv\n");
  EXPECT_THAT(error_of([&] { read_file_listing(bad_number, "freq_hz"); }), HasSubstr(bad_number + ":3:1: expected a number"));
  const auto missing = scratch.write("m.csv", "freq_hz,file\n10,b.csv\n");
  EXPECT_THAT(error_of([&] { read_file_listing(missing, "freq_hz"); }), HasSubstr(missing + ":2:4: data file 'b.csv' not found"));
  const auto columns = scratch.write("c.csv", "freq_hz,file\n10,a.csv,extra\n");
  EXPECT_THAT(error_of([&] { read_file_listing(columns, "freq_hz"); }), HasSubstr(columns + ":2:1: 3 columns"));
  const auto header = scratch.write("h.csv", "frequency,file\n10,a.csv\n");
  EXPECT_THAT(error_of([&] { read_file_listing(header, "freq_hz"); }), HasSubstr("header row naming the columns 'freq_hz'"));
  const auto empty = scratch.write("e.csv", "");
  EXPECT_THAT(error_of([&] { read_file_listing(empty, "freq_hz"); }), HasSubstr("empty listing"));
  const auto no_rows = scratch.write("r.csv", "freq_hz,file\n");
  EXPECT_THAT(error_of([&] { read_file_listing(no_rows, "freq_hz"); }), HasSubstr("names no files"));
}

TEST(FrequencyResponseTable, ReadsDegreesAndChecksEachRow) {
  ScratchDirectory scratch;
  const auto good = scratch.write("g.csv", "freq_hz,gain,phase_deg\n10,1,-90\n20,0.5,-180\n");
  const auto points = read_frequency_response(good);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_NEAR(points[1].phase_rad, -3.14159265358979323846, 1e-15);
  const auto zero = scratch.write("z.csv", "freq_hz,gain,phase_deg\n0,1,0\n");
  EXPECT_THAT(error_of([&] { read_frequency_response(zero); }), HasSubstr(zero + ":2"));
  const auto gain = scratch.write("k.csv", "freq_hz,gain,phase_deg\n10,1,0\n20,-1,0\n");
  EXPECT_THAT(error_of([&] { read_frequency_response(gain); }), HasSubstr(gain + ":3: gain -1 is not positive"));
}

TEST(AngularVibrationRecords, FrequenciesMustIncrease) {
  ScratchDirectory scratch;
  const auto record = scratch.write("v.csv", "time_s,output,angle_deg\n0,0,0\n");
  const std::vector<ListedFile> runs = {{20.0, record, {"list.csv", 2, 1}}, {10.0, record, {"list.csv", 3, 1}}};
  EXPECT_THAT(error_of([&] { read_angular_vibration_records(runs, "time_s", "output", "angle_deg"); }),
              HasSubstr("list.csv:3:1: frequency 10 Hz is not above"));
}

// A time going back (or the record pasted twice) was accepted silently, as other readers refuse it.
TEST(AngularVibrationRecords, TimeMustIncrease) {
  ScratchDirectory scratch;
  const auto record = scratch.write("v.csv", "time_s,output,angle_deg\n0,0,0\n0.001,1,1\n0.0005,2,2\n");
  const std::vector<ListedFile> runs = {{20.0, record, {"list.csv", 2, 1}}};
  EXPECT_THAT(error_of([&] { read_angular_vibration_records(runs, "time_s", "output", "angle_deg"); }),
              HasSubstr(record + ":4:1: time 0.0005 s does not follow the previous time 0.001 s: times must increase"));
}

}  // namespace
}  // namespace inertest

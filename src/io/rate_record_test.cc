// The streaming record reader on small files.
#include "inertest/io/rate_record.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "inertest/core/error.h"
#include "inertest/io/text_table.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::vector<double> read_all(const RateRecordSource& source) {
  std::vector<double> all;
  read_rate_record(source, [&](std::span<const double> s) { all.insert(all.end(), s.begin(), s.end()); });
  return all;
}

TEST(RateRecord, TextWithHeaderCommentsAndColumns) {
  testing::ScratchDirectory dir;
  const std::string path = dir.write("r.csv", "# comment\ntime,rate\n0,1.5\n\n1, 2.5\r\n2,-3e-1\n");
  RateRecordSource source{path, RateRecordFormat::kCsv, ColumnSelector::parse("rate")};
  EXPECT_THAT(read_all(source), ElementsAre(1.5, 2.5, -0.3));
  source.column = ColumnSelector::parse("1");
  EXPECT_THAT(read_all(source), ElementsAre(0, 1, 2));
  const std::string spaced = dir.write("s.txt", "  1 10\n2   20\n");
  EXPECT_THAT(read_all({spaced, RateRecordFormat::kCsv, ColumnSelector::parse("2")}), ElementsAre(10, 20));
  const std::string single = dir.write("one.csv", "4\n5\n6");
  EXPECT_THAT(read_all({single, RateRecordFormat::kCsv, std::nullopt}), ElementsAre(4, 5, 6));
}

// R's write.csv and many loggers quote the header names (RFC 4180); a column is still asked for by
// its name without the quotes.
TEST(RateRecord, QuotedHeaderAndFields) {
  testing::ScratchDirectory dir;
  const std::string path = dir.write("q.csv", "\"gx_dps\",\"gy_dps\",\"gz_dps\"\n1,2,3\n\"4\",\"5\",\"6\"\n");
  EXPECT_THAT(read_all({path, RateRecordFormat::kCsv, ColumnSelector::parse("gz_dps")}), ElementsAre(3, 6));
}

TEST(RateRecord, BadTextNamesFileLineAndColumn) {
  testing::ScratchDirectory dir;
  const std::string path = dir.write("bad.csv", "t,rate\n0,1\n1,abc\n");
  try {
    read_all({path, RateRecordFormat::kCsv, ColumnSelector::parse("rate")});
    FAIL() << "no error";
  } catch (const Error& e) {
    ASSERT_TRUE(e.location().has_value());
    EXPECT_EQ(e.location()->line, 3u);
    EXPECT_EQ(e.location()->column, 3u);
  }
  EXPECT_THROW(read_all({path, RateRecordFormat::kCsv, std::nullopt}), Error);           // two columns
  EXPECT_THROW(read_all({path, RateRecordFormat::kCsv, ColumnSelector::parse("x")}), Error);  // no such name
  EXPECT_THROW(read_all({path, RateRecordFormat::kCsv, ColumnSelector::parse("3")}), Error);
  const std::string missing = dir.write("short.csv", "1,2\n3\n");
  EXPECT_THROW(read_all({missing, RateRecordFormat::kCsv, ColumnSelector::parse("2")}), Error);
  const std::string empty = dir.write("empty.csv", "# nothing\n");
  EXPECT_THROW(read_all({empty, RateRecordFormat::kCsv, std::nullopt}), Error);
  RateRecordSource unknown;
  EXPECT_THROW(unknown.set_format("f16"), Error);
}

TEST(RateRecord, BinaryRecords) {
  testing::ScratchDirectory dir;
  const std::string path = dir.write("r.f64", testing::f64_bytes({1.0, -2.0, 0.5}));
  EXPECT_THAT(read_all({path, RateRecordFormat::kBinary, std::nullopt}), ElementsAre(1.0, -2.0, 0.5));  // f64 by default
  const float narrow[2] = {1.5F, 2.5F};
  const std::string f32 = dir.write("r.f32", std::string(reinterpret_cast<const char*>(narrow), sizeof narrow));
  EXPECT_THAT(read_all({f32, RateRecordFormat::kBinary, std::nullopt, BinaryFormat::parse("f32")}), ElementsAre(1.5, 2.5));
  const std::string ragged = dir.write("ragged.f64", testing::f64_bytes({1.0}) + "abc");
  EXPECT_THROW(read_all({ragged, RateRecordFormat::kBinary, std::nullopt}), Error);
  const std::string nan = dir.write("nan.f64", testing::f64_bytes({1.0, std::numeric_limits<double>::quiet_NaN()}));
  EXPECT_THROW(read_all({nan, RateRecordFormat::kBinary, std::nullopt}), Error);
  // Integers of either byte order, named as the other commands name them ("i32be"), exactly; a
  // record longer than one read chunk keeps its samples across the chunks' seams.
  std::string i32be;
  std::string i16;
  std::vector<double> expected;
  for (std::int32_t i = 0; i < 100000; ++i) {
    const std::int32_t v = (i % 7 == 0 ? -1 : 1) * (i * 7919 % 2000003);
    for (int b = 3; b >= 0; --b) i32be += static_cast<char>((static_cast<std::uint32_t>(v) >> (8 * b)) & 0xFF);
    const auto s = static_cast<std::int16_t>(v % 32768);
    i16 += static_cast<char>(static_cast<std::uint16_t>(s) & 0xFF);
    i16 += static_cast<char>(static_cast<std::uint16_t>(s) >> 8);
    expected.push_back(v);
  }
  RateRecordSource big;
  big.path = dir.write("r.i32be", i32be);
  big.set_format("i32be");
  EXPECT_EQ(read_all(big), expected);
  RateRecordSource little;
  little.path = dir.write("r.i16", i16);
  little.set_format("i16");
  const std::vector<double> shorts = read_all(little);
  ASSERT_EQ(shorts.size(), expected.size());
  for (std::size_t i = 0; i < shorts.size(); ++i) ASSERT_EQ(shorts[i], std::fmod(expected[i], 32768.0)) << i;
  little.path = dir.write("odd.i16", i16 + "x");
  EXPECT_THAT([&] { read_all(little); }, ::testing::ThrowsMessage<Error>(HasSubstr("not a whole number of 2-byte samples (1 trailing bytes)")));
}

// A destination that gives rooms of 1, 2, .. 7 slots in turn: the reader writes into each no more
// than it has, and the samples come out as read_rate_record hands them over; a bad sample is
// named by its number in the record, not in its read.
class SmallRooms final : public SampleDestination {
 public:
  std::span<double> room() override {
    slots_.assign(next_ = next_ % 7 + 1, 0.0);
    return slots_;
  }
  void filled(std::size_t count) override {
    EXPECT_LE(count, slots_.size());
    samples.insert(samples.end(), slots_.begin(), slots_.begin() + static_cast<std::ptrdiff_t>(count));
  }
  std::vector<double> samples;

 private:
  std::vector<double> slots_;
  std::size_t next_ = 0;
};

TEST(RateRecord, BinaryRecordIntoADestination) {
  testing::ScratchDirectory dir;
  std::vector<double> values;
  for (int i = 0; i < 1000; ++i) values.push_back(0.25 * i - 7.0);
  for (const char* format : {"f64", "f32be", "i16"}) {
    RateRecordSource source;
    source.set_format(format);
    std::string bytes;
    for (double v : values) {
      if (source.binary.type == BinaryFormat::SampleType::kFloat64) {
        bytes += testing::f64_bytes({v});
      } else if (source.binary.type == BinaryFormat::SampleType::kFloat32) {
        const auto word = std::bit_cast<std::uint32_t>(static_cast<float>(v));
        for (int b = 3; b >= 0; --b) bytes += static_cast<char>((word >> (8 * b)) & 0xFF);
      } else {
        const auto word = static_cast<std::uint16_t>(static_cast<std::int16_t>(v * 4));
        bytes += static_cast<char>(word & 0xFF);
        bytes += static_cast<char>(word >> 8);
      }
    }
    source.path = dir.write(std::string("r.") + format, bytes);
    SmallRooms rooms;
    EXPECT_EQ(read_binary_rate_record(source, rooms), values.size()) << format;
    EXPECT_EQ(rooms.samples, read_all(source)) << format;
  }
  std::vector<double> bad = values;
  bad[600] = std::numeric_limits<double>::infinity();
  RateRecordSource source{dir.write("inf.f64", testing::f64_bytes(bad)), RateRecordFormat::kBinary, std::nullopt};
  SmallRooms rooms;
  EXPECT_THAT([&] { read_binary_rate_record(source, rooms); },
              ::testing::ThrowsMessage<Error>(HasSubstr("sample 601 is not a finite number")));
}

// Every text file of the bad-input corpus, read as a rate record and as a table: the same values,
// or the same error (message, file, line and column) from both.
class CorpusRecord : public ::testing::TestWithParam<std::string> {};

TEST_P(CorpusRecord, StreamingAndWholeReadersAgree) {
  const std::string path = testing::source_path("tests/corpus/" + GetParam());
  TextTableOptions options;
  options.columns = {ColumnSelector::parse("1")};
  std::string whole_error;
  std::vector<double> whole;
  try {
    whole = read_text_table(path, options).columns.front();
  } catch (const Error& e) {
    whole_error = e.what();
  }
  std::string stream_error;
  std::vector<double> streamed;
  try {
    streamed = read_all({path, RateRecordFormat::kCsv, ColumnSelector::parse("1")});
  } catch (const Error& e) {
    stream_error = e.what();
  }
  EXPECT_EQ(stream_error, whole_error);
  EXPECT_EQ(streamed, whole);
}

std::vector<std::string> corpus_text_files() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(testing::source_path("tests/corpus"))) {
    if (entry.path().extension() == ".csv") names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

INSTANTIATE_TEST_SUITE_P(BadInputCorpus, CorpusRecord, ::testing::ValuesIn(corpus_text_files()),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           std::string name = param_info.param.substr(0, param_info.param.size() - 4);
                           std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
                           return name;
                         });

// A record long enough to be parsed in several chunks at once: every value arrives once, in order,
// and an error on its last lines names its exact line and column.
TEST(RateRecord, LongTextRecordAcrossBuffers) {
  testing::ScratchDirectory dir;
  testing::UniformSequence uniform;
  constexpr std::size_t kRows = 600'000;  // about 15 MB
  std::vector<double> values(kRows);
  std::string text = "time;rate\n";
  for (std::size_t i = 0; i < kRows; ++i) {
    values[i] = std::round(1e6 * uniform.next()) / 1e6;
    text += std::to_string(i) + ";" + std::to_string(values[i]) + "\n";
  }
  const std::string path = dir.write("long.csv", text);
  const std::vector<double> read = read_all({path, RateRecordFormat::kCsv, ColumnSelector::parse("rate")});
  ASSERT_EQ(read.size(), kRows);
  for (std::size_t i = 0; i < kRows; ++i) ASSERT_NEAR(read[i], values[i], 1e-12) << "row " << i;

  const std::string bad = dir.write("bad.csv", text + "600000;1,25\n" + "600001;0.5\n");
  try {
    read_all({bad, RateRecordFormat::kCsv, ColumnSelector::parse("rate")});
    FAIL() << "a decimal comma on the last lines must be an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.location()->line, kRows + 2);
    EXPECT_EQ(e.location()->column, 8u);
    EXPECT_THAT(e.message(), HasSubstr("'1,25' in column 'rate' looks like a decimal comma"));
  }
}

TEST(RateRecord, SameMessagesAsTheTableReader) {
  testing::ScratchDirectory dir;
  const auto message = [&](const std::string& content, const std::string& column) {
    try {
      read_all({dir.write("r.csv", content), RateRecordFormat::kCsv, ColumnSelector::parse(column)});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string file = dir.path() + "/r.csv";
  EXPECT_EQ(message("t;rate\n0;1,25\n", "rate"),
            file + ":2:3: '1,25' in column 'rate' looks like a decimal comma; inertest expects a decimal point");
  EXPECT_EQ(message("t,rate\n0,1\nt,rate\n", "rate"), file + ":3:1: a second header row in the data (records joined together?)");
  EXPECT_EQ(message("t,rate\n0,nan\n", "rate"),
            file + ":2:3: 'nan' is not a finite number (NaN and Inf are not accepted)");
  EXPECT_EQ(message("t,rate\n0,1\n1", "rate"),
            file + ":3:2: expected 2 columns, found 1 (the last line has no line end: a truncated record?)");
  EXPECT_EQ(message("t,rate\n0,1\n1;2\n", "rate"),
            file + ":3:2: expected 2 columns, found 1 (this line is separated by ';', the record by ',': mixed delimiters)");
  EXPECT_EQ(message("t,rate\n", "rate"), file + ": expected at least 1 data rows, found 0");
}

}  // namespace
}  // namespace inertest

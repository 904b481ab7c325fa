// The chunked parallel parse gives the same table and the same errors, with the same line numbers,
// whatever the thread count and wherever the chunks fall.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#include "inertest/core/error.h"
#include "inertest/io/text_table.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;

// A record of `rows` rows with comments and blank lines sprinkled in, so that chunk boundaries
// fall next to skipped lines as well.
std::string record(std::size_t rows) {
  std::string text = "# header comment\ntime,gyro,temperature\n";
  for (std::size_t i = 0; i < rows; ++i) {
    if (i % 17 == 5) text += "# a comment line\n";
    if (i % 23 == 7) text += "\n";
    text += std::to_string(i) + "e-2," + std::to_string(static_cast<double>(i % 101) * 1.25e-3) + ",20." +
            std::to_string(i % 10) + "\n";
  }
  return text;
}

TextTable parse_with(const std::string& text, std::size_t threads) {
  TextTableOptions options;
  options.threads = threads;
  options.minimum_chunk_bytes = 1;  // one chunk per thread even for a small record
  return parse_text_table(text, "rec.csv", options);
}

std::string error_with(const std::string& text, std::size_t threads) {
  try {
    parse_with(text, threads);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(TextTableThreads, SameTableWhateverTheThreadCount) {
  const std::string text = record(1000);
  const TextTable one = parse_with(text, 1);
  ASSERT_EQ(one.rows(), 1000u);
  for (std::size_t threads : {2, 3, 7, 64}) {
    const TextTable many = parse_with(text, threads);
    EXPECT_EQ(many.columns, one.columns) << threads << " threads";
    EXPECT_EQ(many.row_lines, one.row_lines) << threads << " threads";
    EXPECT_EQ(many.first_data_line, one.first_data_line) << threads << " threads";
  }
  EXPECT_EQ(one.first_data_line, 3u);
  // The last row is the last line.
  EXPECT_EQ(one.row_lines.back(), static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')));
}

TEST(TextTableThreads, TheFirstErrorInFileOrderWins) {
  std::string text = record(1000);
  // Two bad cells: the one on the earlier line is reported, from whichever chunk it falls in.
  text.replace(text.find("\n400e-2,") + 1, 3, "4x0");
  text.replace(text.find("\n900e-2,") + 1, 3, "9x0");
  const std::string expected = error_with(text, 1);
  EXPECT_THAT(expected, HasSubstr("rec.csv:"));
  EXPECT_THAT(expected, HasSubstr("found '4x0e-2'"));
  for (std::size_t threads : {2, 3, 7, 64}) EXPECT_EQ(error_with(text, threads), expected) << threads << " threads";
}

TEST(TextTableThreads, EnvironmentSetsTheCount) {
  ::setenv("INERTEST_THREADS", "two", 1);
  TextTableOptions options;
  options.minimum_chunk_bytes = 1;
  EXPECT_THROW(parse_text_table("a\n1\n2\n", "rec.csv", options), Error);
  ::setenv("INERTEST_THREADS", "2", 1);
  EXPECT_EQ(parse_text_table(record(50), "rec.csv", options).rows(), 50u);
  ::unsetenv("INERTEST_THREADS");
}

TEST(TextTable, LocatesACellAfterReading) {
  testing::ScratchDirectory dir;
  const std::string path = dir.write("r.csv", "# c\nt ; v\n0 ; 1\n\n1 ;   2\n");
  const TextTable table = read_text_table(path);
  EXPECT_EQ(table.header_line, 2u);
  EXPECT_EQ(locate_cell(table, 1, 1).to_string(), path + ":5:7");
  EXPECT_EQ(locate_cell(table, 0, 0).to_string(), path + ":3:1");
  // From memory there is no file to look in: the line only.
  const TextTable in_memory = parse_text_table("t,v\n0,1\n", "mem.csv");
  EXPECT_EQ(locate_cell(in_memory, 0, 1).to_string(), "mem.csv:2");
}

}  // namespace
}  // namespace inertest

#include "io/decimal.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace inertest::io_detail {
namespace {

// parse_decimal against fast_float::from_chars on `text` followed by each of several tails (none:
// the text ends the buffer and the digits are read one by one; a delimiter, a line end or garbage
// with bytes enough after it for the eight-byte reads): the same ec, the same end, the same bits.
void expect_as_fast_float(const std::string& text) {
  for (const std::string tail : {"", ",", "\n0.25,1", "x", "e", "e+", ".5", "  \r\n", "12345678,"}) {
    const std::string buffer = text + tail;
    const char* first = buffer.data();
    const char* last = first + buffer.size();
    double expected = -7.0;
    double actual = -7.0;
    const auto want = fast_float::from_chars(first, last, expected);
    const auto got = parse_decimal(first, last, actual);
    EXPECT_EQ(got.ec, want.ec) << "'" << buffer << "'";
    EXPECT_EQ(got.ptr - first, want.ptr - first) << "'" << buffer << "'";
    EXPECT_EQ(std::bit_cast<std::uint64_t>(actual), std::bit_cast<std::uint64_t>(expected))
        << "'" << buffer << "': " << actual << " vs " << expected;
  }
}

class DecimalEdgeCases : public ::testing::TestWithParam<const char*> {};

TEST_P(DecimalEdgeCases, ParseAsFastFloat) { expect_as_fast_float(GetParam()); }

INSTANTIATE_TEST_SUITE_P(
    Decimal, DecimalEdgeCases,
    ::testing::Values("0", "-0", "0.0", "-0.0", "-0.000000", "1", "-1", "0.123456", "-0.123456", "123456.789012",
                      "00000000000000000000000001", "000.000", "1.", "-1.", ".5", "-.5", ".", "-.", "-", "", "+1",
                      "--1", "-+1", "1..2", "1.2.3",
                      // 19 and 20 significant digits, leading zeros before them, 2^64 and beyond.
                      "1234567890123456789", "12345678901234567890", "9999999999999999999", "99999999999999999999",
                      "0.1234567890123456789", "0.12345678901234567890", "0000000000000000000012345",
                      "18446744073709551615", "18446744073709551616", "123456789012345678901234567890",
                      // 2^53 - 1, 2^53, 2^53 + 1 (not exact), 2^53 + 2.
                      "9007199254740991", "9007199254740992", "9007199254740993", "9007199254740994",
                      "900719925474099.3", "0.9007199254740993",
                      // Exponents: at the edge of the exact powers, beyond, without digits, very long.
                      "1e22", "1e23", "1e-22", "1e-23", "1E5", "1e+5", "1e-5", "1.5e-3", "-2.5E+10", "1e", "1e+",
                      "1e-", "1ex", "1e0022", "1e999", "1e-999", "1e400", "-1e400", "4.9e-324", "2.2250738585072014e-308",
                      "1.7976931348623157e308", "1.7976931348623159e308", "12345e-27", "0e999", "0.000001e-20",
                      // Not numbers, or numbers fast_float reads as such (inf, nan).
                      "inf", "-inf", "Infinity", "nan", "NaN", "-nan", "abc", "1,5", "0x10", " 1", "\"1\"", "1 2",
                      "12345678.12345678", "87654321", "876543210", "0.00000000", "1234567,", "12345678e1",
                      "123456789012345678.9", "1234567890123456789.0", "0.30000000000000004", "0.1", "0.2", "0.3"),
    [](const ::testing::TestParamInfo<const char*>& param) { return "case" + std::to_string(param.index); });

// A random decimal: sign, integer and fraction digits (none to 21 each), an exponent of up to four
// digits, sometimes a byte after it that a cell could hold.
std::string random_decimal(std::mt19937_64& random) {
  const auto pick = [&random](int n) { return static_cast<int>(random() % static_cast<std::uint64_t>(n)); };
  const auto digits = [&](int count) {
    std::string out;
    for (int i = 0; i < count; ++i) out += static_cast<char>('0' + pick(10));
    return out;
  };
  std::string text;
  if (pick(2) == 0) text += '-';
  text += digits(pick(22));
  if (pick(3) != 0) text += '.' + digits(pick(22));
  if (pick(4) == 0) {
    text += pick(2) == 0 ? 'e' : 'E';
    const int sign = pick(3);
    if (sign == 1) text += '-';
    if (sign == 2) text += '+';
    text += digits(pick(5));
  }
  if (pick(10) == 0) text += "x,e.-+\n"[pick(7)];
  return text;
}

TEST(Decimal, RandomTextParsesAsFastFloat) {
  std::mt19937_64 random(20240519);
  for (int i = 0; i < 200000; ++i) expect_as_fast_float(random_decimal(random));
}

// Every double printed as %.6f (the bench's format) and as the shortest text that reads it back.
TEST(Decimal, PrintedDoublesParseAsFastFloat) {
  std::mt19937_64 random(15);
  std::normal_distribution<double> normal(0.0, 1.0);
  char text[64];
  for (int i = 0; i < 100000; ++i) {
    const double value = normal(random) * std::pow(10.0, static_cast<int>(random() % 20) - 10);
    std::snprintf(text, sizeof text, "%.6f", value);
    expect_as_fast_float(text);
    std::snprintf(text, sizeof text, "%.17g", value);
    expect_as_fast_float(text);
  }
}

}  // namespace
}  // namespace inertest::io_detail

// The number parser of the text records: a plain decimal ([-]digits[.digits][e[+-]digits], the cell
// of nearly every lab CSV) read directly, anything else handed to fast_float. Private to io.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fast_float/fast_float.h>

namespace inertest::io_detail {

// fast_float::from_chars(first, last, value) for a double, with the same result in every case
// (value bit for bit, ptr, ec) under the default rounding mode (to nearest; inertest never changes
// it). A decimal of at most 19 digits whose mantissa m is at most 2^53 and whose power of ten e is
// within [-22, 22] is m * 10^e or m / 10^-e in one correctly rounded IEEE operation, both operands
// being exact: Clinger's fast path (W. D. Clinger, "How to read floating point numbers accurately",
// PLDI 1990), the one fast_float takes first (D. Lemire, "Number parsing at a gigabyte per second",
// Software: Practice and Experience 51(8), 2021, section 5). Its digits are read eight at a time
// (SWAR, ibid. section 4). Every other text (more digits, a larger exponent, "inf", no digit at all)
// goes to fast_float itself.
[[gnu::always_inline]] inline fast_float::from_chars_result parse_decimal(const char* first, const char* last,
                                                                    double& value);

// fast_float::from_chars, out of line: the rare path of parse_decimal.
fast_float::from_chars_result parse_decimal_slowly(const char* first, const char* last, double& value);

// The eight bytes at p as one word, the first byte in the lowest: the order the SWAR loops of the
// text readers (here and in text_rows.cc) assume.
inline std::uint64_t load_eight_bytes(const char* p) {
  std::uint64_t word = 0;
  std::memcpy(&word, p, 8);
  if constexpr (std::endian::native == std::endian::big) word = __builtin_bswap64(word);
  return word;
}

namespace decimal_detail {

inline constexpr std::uint64_t kOnes = 0x0101010101010101ULL;

// The value of eight bytes holding digits, the first in the lowest byte; a byte 0x00 counts as the
// digit 0 (Lemire, op. cit., section 4: the multiplications combine pairs, quadruples, octets).
inline std::uint64_t eight_digits(std::uint64_t word) {
  word = ((word & (0x0F * kOnes)) * (10 * 256 + 1)) >> 8;
  word = ((word & 0x00FF00FF00FF00FFULL) * (100 * 65536 + 1)) >> 16;
  return ((word & 0x0000FFFF0000FFFFULL) * (10000ULL * (1ULL << 32) + 1)) >> 32;
}

inline constexpr std::array<std::uint64_t, 9> kIntegerPowers = {1,      10,      100,      1000,     10000,
                                                                100000, 1000000, 10000000, 100000000};

// The bytes of `word` that are not digits, their top bit set: a byte b is a digit when neither
// b + 0x46 nor b - 0x30 sets its top bit. The lowest byte flagged is the first non-digit (the digits
// below it carry and borrow nothing); the bytes above it may be flagged or not.
inline std::uint64_t non_digits(std::uint64_t word) {
  return ((word + 0x46 * kOnes) | (word - 0x30 * kOnes)) & (0x80 * kOnes);
}

// One step of read_digits on `word`, the eight bytes at p, and flagged = non_digits(word). Adds the
// digits to mantissa and count and moves p past them; true when all eight were digits (more may
// follow).
inline bool read_eight(std::uint64_t word, std::uint64_t flagged, const char*& p, std::uint64_t& mantissa,
                       int& count) {
  if (flagged == 0) {
    mantissa = mantissa * 100000000 + eight_digits(word);
    p += 8;
    count += 8;
    return true;
  }
  const int digits = std::countr_zero(flagged) / 8;
  if (digits > 0) {
    // The digits moved to the top bytes, zeros below them: the same number.
    mantissa = mantissa * kIntegerPowers[digits] + eight_digits(word << (8 * (8 - digits)));
    count += digits;
  }
  p += digits;
  return false;
}

// Reads the digits at p into mantissa (mantissa * 10 + digit each, wrapping as fast_float's does when
// there are more than 19) and count; returns the first byte that is not a digit. Eight bytes a step
// while eight remain before last.
inline const char* read_digits(const char* p, const char* last, std::uint64_t& mantissa, int& count) {
  while (last - p >= 8) {
    const std::uint64_t word = load_eight_bytes(p);
    if (!read_eight(word, non_digits(word), p, mantissa, count)) return p;
  }
  for (; p != last && static_cast<unsigned char>(*p - '0') < 10; ++p, ++count) {
    mantissa = mantissa * 10 + static_cast<std::uint64_t>(*p - '0');
  }
  return p;
}

inline constexpr std::array<double, 23> kExactPowers = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                                        1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                                        1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

}  // namespace decimal_detail

[[gnu::always_inline]] inline fast_float::from_chars_result parse_decimal(const char* first, const char* last,
                                                                    double& value) {
  using namespace decimal_detail;
  // The sign without a branch: the signs of a noise record are as random as a coin, and a branch
  // mispredicted on every other number (the six-channel bench record parsed on one thread in
  // 256-293 ms with it, 242-244 ms without). With nine bytes, the eight at `first` and the eight
  // after it are loaded and their digits found side by side, and the sign picks one of each by a
  // mask, so that nothing waits for the sign but the choice (loading after the sign made a record
  // of one sign 8 % slower to parse; this, 3 %). The empty asm hides the sign from GCC, which
  // otherwise turns the choice back into a branch.
  const bool long_enough = last - first >= 9;
  std::uint64_t at_first = 0;
  std::uint64_t after_sign = 0;
  std::uint64_t negative = 0;
  if (long_enough) {
    at_first = load_eight_bytes(first);
    after_sign = load_eight_bytes(first + 1);
    negative = static_cast<std::uint64_t>((at_first & 0xFF) == static_cast<unsigned char>('-'));
  } else {
    negative = static_cast<std::uint64_t>(first != last && *first == '-');
  }
#if defined(__GNUC__)
  __asm__("" : "+r"(negative));
#endif
  const char* p = first + negative;
  std::uint64_t mantissa = 0;
  int digits = 0;
  const std::uint64_t choose_after_sign = 0 - negative;
  const auto chosen = [choose_after_sign](std::uint64_t a, std::uint64_t b) { return a ^ ((a ^ b) & choose_after_sign); };
  if (!long_enough || read_eight(chosen(at_first, after_sign), chosen(non_digits(at_first), non_digits(after_sign)), p,
                                 mantissa, digits)) {
    p = read_digits(p, last, mantissa, digits);
  }
  int exponent = 0;
  if (p != last && *p == '.') {
    const int integer_digits = digits;
    p = read_digits(p + 1, last, mantissa, digits);
    exponent = integer_digits - digits;
  }
  if (p != last && (*p == 'e' || *p == 'E')) {
    // At most three exponent digits; an 'e' without digits (fast_float stops before it) goes the slow way.
    const char* q = p + 1;
    const bool negative_exponent = q != last && *q == '-';
    if (q != last && (*q == '-' || *q == '+')) ++q;
    std::uint64_t explicit_exponent = 0;
    int exponent_digits = 0;
    q = read_digits(q, last, explicit_exponent, exponent_digits);
    if (exponent_digits == 0 || exponent_digits > 3) return parse_decimal_slowly(first, last, value);
    exponent += negative_exponent ? -static_cast<int>(explicit_exponent) : static_cast<int>(explicit_exponent);
    p = q;
  }
  if (digits == 0 || digits > 19 || mantissa > (std::uint64_t{1} << 53) || exponent < -22 || exponent > 22) {
    return parse_decimal_slowly(first, last, value);
  }
  double result = static_cast<double>(mantissa);
  result = exponent < 0 ? result / kExactPowers[static_cast<std::size_t>(-exponent)]
                        : result * kExactPowers[static_cast<std::size_t>(exponent)];
  value = std::bit_cast<double>(std::bit_cast<std::uint64_t>(result) | negative << 63);  // result >= +0
  return {p, std::errc()};
}

}  // namespace inertest::io_detail

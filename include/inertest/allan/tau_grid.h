// Averaging times of an Allan analysis: tau = m * tau0 with integer averaging factors m.
//
// Grid specifications (as the CLI flag --taus and the plan key `taus` take them):
//   "octave"     m = 1, 2, 4, 8, ...                      (IEEE Std 952-1997 C.1, powers of two)
//   "decade"     m = 1, 2, 4, 10, 20, 40, 100, ...        (Stable32 / allantools "decade")
//   "all"        every m = 1, 2, 3, ...
//   "N/decade"   N points per decade, m = round(10^(i/N)), duplicates dropped (e.g. "10/decade")
//   "0.1,1,10"   an explicit list of tau in seconds (also Kind::kExplicit with taus_s set, as Python's
//                list or array of taus): m = round(tau * rate) when |tau * rate - m| <= 1e-6 * max(1, tau * rate),
//                an Error otherwise (a tau between two samples is not rounded to either).
// Averaging factors the record cannot support (m > the largest factor allowed) are left out.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace inertest {

struct TauGrid {
  enum class Kind { kOctave, kDecade, kAll, kPerDecade, kExplicit };
  Kind kind = Kind::kOctave;
  std::size_t points_per_decade = 0;  // kPerDecade
  std::vector<double> taus_s;         // kExplicit, in seconds, as given

  // Parses a specification; throws Error naming what is wrong.
  static TauGrid parse(std::string_view text);
  std::string to_string() const;

  // The sorted, distinct averaging factors m <= largest_factor for sample rate `sample_rate_hz`.
  // Throws Error when an explicit tau is not a positive whole number of sample intervals.
  std::vector<std::size_t> averaging_factors(double sample_rate_hz, std::size_t largest_factor) const;
};

}  // namespace inertest

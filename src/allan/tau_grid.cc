#include "inertest/allan/tau_grid.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fast_float/fast_float.h>
#include <fmt/format.h>

#include "inertest/core/error.h"

namespace inertest {
namespace {

std::string_view trim(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  return text;
}

[[noreturn]] void bad_spec(std::string_view text, const std::string& why) {
  throw Error("bad tau specification '" + std::string(text) + "': " + why +
              " (expected octave, decade, all, N/decade or a comma list of tau in seconds)");
}

}  // namespace

TauGrid TauGrid::parse(std::string_view text) {
  const std::string_view spec = trim(text);
  TauGrid grid;
  if (spec == "octave") return grid;
  if (spec == "decade") {
    grid.kind = Kind::kDecade;
    return grid;
  }
  if (spec == "all") {
    grid.kind = Kind::kAll;
    return grid;
  }
  if (spec.empty()) bad_spec(text, "it is empty");
  if (spec.ends_with("/decade")) {
    const std::string_view count = trim(spec.substr(0, spec.size() - 7));
    std::size_t n = 0;
    const auto [end, error] = std::from_chars(count.data(), count.data() + count.size(), n);
    if (error != std::errc() || end != count.data() + count.size() || n == 0 || n > 1000) {
      bad_spec(text, "the number of points per decade must be a whole number from 1 to 1000");
    }
    grid.kind = Kind::kPerDecade;
    grid.points_per_decade = n;
    return grid;
  }
  grid.kind = Kind::kExplicit;
  std::string_view rest = spec;
  while (true) {
    const std::size_t comma = rest.find(',');
    const std::string_view item = trim(rest.substr(0, comma));
    double tau = 0.0;
    const auto [end, error] = fast_float::from_chars(item.data(), item.data() + item.size(), tau);
    if (item.empty() || error != std::errc() || end != item.data() + item.size()) {
      bad_spec(text, fmt::format("'{}' is not a number", item));
    }
    if (!(tau > 0.0) || !std::isfinite(tau)) bad_spec(text, fmt::format("tau must be positive, got '{}'", item));
    grid.taus_s.push_back(tau);
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  return grid;
}

std::string TauGrid::to_string() const {
  switch (kind) {
    case Kind::kOctave: return "octave";
    case Kind::kDecade: return "decade";
    case Kind::kAll: return "all";
    case Kind::kPerDecade: return std::to_string(points_per_decade) + "/decade";
    case Kind::kExplicit: break;
  }
  std::string text;
  for (double tau : taus_s) {
    if (!text.empty()) text += ",";
    char buffer[32];
    const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, tau);
    text.append(buffer, end);
  }
  return text;
}

std::vector<std::size_t> TauGrid::averaging_factors(double sample_rate_hz, std::size_t largest_factor) const {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw Error("the sample rate must be positive and finite");
  }
  std::vector<std::size_t> factors;
  switch (kind) {
    case Kind::kOctave:
      for (std::size_t m = 1; m <= largest_factor; m *= 2) {
        factors.push_back(m);
        if (m > largest_factor / 2) break;
      }
      break;
    case Kind::kDecade:
      for (std::size_t decade = 1; decade <= largest_factor; decade *= 10) {
        for (std::size_t step : {1, 2, 4}) {
          if (decade * step <= largest_factor) factors.push_back(decade * step);
        }
        if (decade > largest_factor / 10) break;
      }
      break;
    case Kind::kAll:
      for (std::size_t m = 1; m <= largest_factor; ++m) factors.push_back(m);
      break;
    case Kind::kPerDecade:
      for (std::size_t i = 0;; ++i) {
        const double m = std::round(std::pow(10.0, static_cast<double>(i) / static_cast<double>(points_per_decade)));
        if (m > static_cast<double>(largest_factor)) break;
        factors.push_back(static_cast<std::size_t>(m));
      }
      break;
    case Kind::kExplicit:
      for (double tau : taus_s) {
        const double exact = tau * sample_rate_hz;
        const double m = std::round(exact);
        if (m < 1.0 || std::abs(exact - m) > 1e-6 * std::max(1.0, exact)) {
          throw Error("tau " + std::to_string(tau) + " s is not a whole number of sample intervals (1/" +
                      std::to_string(sample_rate_hz) + " Hz)");
        }
        if (m <= static_cast<double>(largest_factor)) factors.push_back(static_cast<std::size_t>(m));
      }
      break;
  }
  std::sort(factors.begin(), factors.end());
  factors.erase(std::unique(factors.begin(), factors.end()), factors.end());
  return factors;
}

}  // namespace inertest

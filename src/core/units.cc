#include "inertest/core/units.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "inertest/core/error.h"

namespace inertest {
namespace {

using constants::kArcsecond;
using constants::kDegree;
using constants::kPi;

struct NamedUnit {
  double factor;
  Dimension::Base base;  // kBaseCount for dimensionless
  int power = 1;         // power of base (whole), e.g. Hz = time^-1
};

Dimension dimension_of(Dimension::Base base, int power) {
  Dimension d;
  if (base != Dimension::kBaseCount) d.half_powers[base] = 2 * power;
  return d;
}

// Named units that are not products of others. Composite ones (g, W, ohm) are expanded below.
const std::unordered_map<std::string_view, NamedUnit>& simple_units() {
  static const std::unordered_map<std::string_view, NamedUnit> table = {
      // angle
      {"rad", {1.0, Dimension::kAngle}},
      {"mrad", {1e-3, Dimension::kAngle}},
      {"urad", {1e-6, Dimension::kAngle}},
      {"deg", {kDegree, Dimension::kAngle}},
      {"°", {kDegree, Dimension::kAngle}},
      {"arcmin", {kDegree / 60.0, Dimension::kAngle}},
      {"arcsec", {kArcsecond, Dimension::kAngle}},
      {"mdeg", {1e-3 * kDegree, Dimension::kAngle}},
      {"rev", {2.0 * kPi, Dimension::kAngle}},
      // time
      {"s", {1.0, Dimension::kTime}},
      {"sec", {1.0, Dimension::kTime}},
      {"ms", {1e-3, Dimension::kTime}},
      {"msec", {1e-3, Dimension::kTime}},
      {"us", {1e-6, Dimension::kTime}},
      {"µs", {1e-6, Dimension::kTime}},  // U+00B5 micro sign
      {"μs", {1e-6, Dimension::kTime}},  // U+03BC Greek mu
      {"ns", {1e-9, Dimension::kTime}},
      {"min", {60.0, Dimension::kTime}},
      {"h", {3600.0, Dimension::kTime}},
      {"hr", {3600.0, Dimension::kTime}},
      {"day", {86400.0, Dimension::kTime}},
      {"Hz", {1.0, Dimension::kTime, -1}},
      {"kHz", {1e3, Dimension::kTime, -1}},
      // length and mass
      {"m", {1.0, Dimension::kLength}},
      {"mm", {1e-3, Dimension::kLength}},
      {"cm", {1e-2, Dimension::kLength}},
      {"km", {1e3, Dimension::kLength}},
      {"kg", {1.0, Dimension::kMass}},
      // temperature: a degree Celsius and a kelvin are the same size, so a difference or a
      // sensitivity (ppm/degC, deg/h/degC) converts by factor 1; an absolute temperature would need
      // the 273.15 offset, which convert() refuses to guess (see there)
      {"degC", {1.0, Dimension::kTemperature}},
      {"°C", {1.0, Dimension::kTemperature}},  // as the report writes it (ppm/°C)
      {"K", {1.0, Dimension::kTemperature}},
      // electrical
      {"V", {1.0, Dimension::kVoltage}},
      {"mV", {1e-3, Dimension::kVoltage}},
      {"uV", {1e-6, Dimension::kVoltage}},
      {"µV", {1e-6, Dimension::kVoltage}},  // U+00B5 micro sign
      {"μV", {1e-6, Dimension::kVoltage}},  // U+03BC Greek mu
      {"kV", {1e3, Dimension::kVoltage}},
      {"A", {1.0, Dimension::kCurrent}},
      {"mA", {1e-3, Dimension::kCurrent}},
      {"uA", {1e-6, Dimension::kCurrent}},
      {"µA", {1e-6, Dimension::kCurrent}},  // U+00B5 micro sign
      {"μA", {1e-6, Dimension::kCurrent}},  // U+03BC Greek mu
      // instrument counts
      {"pulse", {1.0, Dimension::kCount}},
      {"count", {1.0, Dimension::kCount}},
      {"LSB", {1.0, Dimension::kCount}},
      // dimensionless ratios
      {"1", {1.0, Dimension::kBaseCount}},
      {"ppm", {1e-6, Dimension::kBaseCount}},
      {"%", {1e-2, Dimension::kBaseCount}},
  };
  return table;
}

struct Parsed {
  double factor = 1.0;
  Dimension dimension;
};

void accumulate(Parsed& into, const Parsed& term, int half_power) {
  into.factor *= std::pow(term.factor, half_power / 2.0);
  for (int i = 0; i < Dimension::kBaseCount; ++i) {
    into.dimension.half_powers[static_cast<std::size_t>(i)] +=
        term.dimension.half_powers[static_cast<std::size_t>(i)] * half_power / 2;
  }
}

// The unit of one name exactly as written, or nullopt.
std::optional<Parsed> exactly_named(std::string_view name) {
  const auto& table = simple_units();
  if (auto it = table.find(name); it != table.end()) {
    return Parsed{it->second.factor, dimension_of(it->second.base, it->second.power)};
  }
  Parsed p;
  auto add = [&p](Dimension::Base base, int half) { p.dimension.half_powers[base] += half; };
  // Standard gravity as a unit of specific force, and its milli- and micro- (mg is milli-g here,
  // as in accelerometer data sheets: inertest has no mass unit but kg).
  if (name == "g" || name == "mg" || name == "ug") {
    p.factor = constants::kStandardGravity * (name == "g" ? 1.0 : name == "mg" ? 1e-3 : 1e-6);
    add(Dimension::kLength, 2);
    add(Dimension::kTime, -4);
    return p;
  }
  if (name == "W" || name == "mW") {
    p.factor = name == "W" ? 1.0 : 1e-3;
    add(Dimension::kVoltage, 2);
    add(Dimension::kCurrent, 2);
    return p;
  }
  if (name == "ohm" || name == "kohm" || name == "Mohm" || name == "MOhm" || name == "Ω" || name == "MΩ" ||
      name == "mohm" || name == "mOhm" || name == "mΩ") {  // mohm: a bond's milliohms (GJB 5.3)
    p.factor = (name == "ohm" || name == "Ω")                     ? 1.0
               : name == "kohm"                                  ? 1e3
               : (name == "mohm" || name == "mOhm" || name == "mΩ") ? 1e-3
                                                                  : 1e6;
    add(Dimension::kVoltage, 2);
    add(Dimension::kCurrent, -2);
    return p;
  }
  // Rates as loggers' headers and data sheets abbreviate them.
  if (name == "rpm" || name == "dps" || name == "dph") {
    p.factor = name == "rpm" ? 2.0 * kPi / 60.0 : name == "dps" ? kDegree : kDegree / 3600.0;
    add(Dimension::kAngle, 2);
    add(Dimension::kTime, -2);
    return p;
  }
  return std::nullopt;
}

// Words for units, read in any case (Deg, DEGREES, Hours): each names one unit, as the table does.
std::optional<std::string_view> word_for_unit(std::string_view lowered) {
  static const std::unordered_map<std::string_view, std::string_view> names = {
      {"deg", "deg"},   {"degree", "deg"}, {"degrees", "deg"}, {"rad", "rad"},     {"radian", "rad"},
      {"radians", "rad"}, {"sec", "s"},    {"second", "s"},    {"seconds", "s"},   {"minute", "min"},
      {"minutes", "min"}, {"hr", "hr"},    {"hour", "h"},      {"hours", "h"},     {"volt", "V"},
      {"volts", "V"},     {"rpm", "rpm"},  {"dps", "dps"},     {"dph", "dph"},     {"arcsec", "arcsec"},
      {"pulses", "pulse"}, {"counts", "count"}, {"cnt", "count"}, {"lsb", "LSB"}};
  const auto it = names.find(lowered);
  return it == names.end() ? std::nullopt : std::optional<std::string_view>(it->second);
}

std::string lower(std::string_view text) {
  std::string lowered(text);
  for (char& c : lowered) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lowered;
}

// Written all in capitals, with two letters or more (DEG/S, MV, as old loggers and some HDF5 and
// TDMS files store units): only such a unit is read in another case. Mixed or lower case is meant
// (mOhm is no megohm), and one capital letter may be another unit (S, G, k).
bool all_capitals(std::string_view whole) {
  std::size_t letters = 0;
  for (const char c : whole) {
    if (std::islower(static_cast<unsigned char>(c)) != 0) return false;
    letters += std::isupper(static_cast<unsigned char>(c)) != 0 ? 1 : 0;
  }
  return letters >= 2;
}

// A unit name: as written; a word for a unit in any case (Deg, degrees, Hours); in capitals
// (all_capitals: the one known name of that spelling in any case, none where two of different sizes
// share it, MOHM); or a name and its whole power run together (s2 in m/s2). An unknown name is an
// Error naming it: a file's header or a channel's unit taken as another, or as none, gave figures
// 3600 times off.
Parsed named(std::string_view name, std::string_view whole) {
  if (const auto exact = exactly_named(name)) return *exact;
  const std::string lowered = lower(name);
  if (const std::optional<std::string_view> word = word_for_unit(lowered)) return *exactly_named(*word);
  if (all_capitals(whole)) {
    std::vector<std::string_view> any_case;  // the known names of this spelling, of different sizes
    const auto consider = [&](std::string_view known) {
      if (lower(known) != lowered) return;
      if (any_case.empty() || exactly_named(any_case.front())->factor != exactly_named(known)->factor) {
        any_case.push_back(known);
      }
    };
    for (const auto& entry : simple_units()) consider(entry.first);
    for (std::string_view known : {"g", "mg", "ug", "W", "mW", "ohm", "kohm", "Mohm", "mohm", "rpm", "dps", "dph"}) {
      consider(known);
    }
    if (any_case.size() == 1) return *exactly_named(any_case.front());
    if (any_case.size() > 1) {
      std::string names;
      for (std::string_view known : any_case) names += (names.empty() ? "" : " or ") + std::string(known);
      throw Error("unit '" + std::string(name) + "' in '" + std::string(whole) + "' is ambiguous in capitals: write " +
                  names);
    }
  }
  const std::size_t digits = name.find_first_of("0123456789");
  if (digits > 0 && digits + 1 == name.size()) {  // one digit: s2, not a number's digits
    Parsed powered;
    accumulate(powered, named(name.substr(0, digits), whole), 2 * std::stoi(std::string(name.substr(digits))));
    return powered;
  }
  throw Error("unknown unit '" + std::string(name) + "' in '" + std::string(whole) +
              "' (known: rad, deg, arcsec, s, h, Hz, g, V, mV, A, pulse, ppm, %, ...)");
}

class UnitParser {
 public:
  explicit UnitParser(std::string_view text) : text_(text) {}

  Parsed parse_all() {
    Parsed result = parse_product();
    skip_spaces();
    if (pos_ != text_.size()) fail("unexpected '" + std::string(1, text_[pos_]) + "'");
    return result;
  }

 private:
  // product := term (('/' | '*' | '.') term)*  -- '/' divides by the next term only.
  Parsed parse_product() {
    Parsed result;
    int sign = 1;
    for (;;) {
      Parsed term = parse_term();
      int half_power = 2 * sign;
      skip_spaces();
      if (peek() == '^') {
        ++pos_;
        half_power = sign * parse_power_in_halves();
      }
      accumulate(result, term, half_power);
      skip_spaces();
      const char c = peek();
      if (c == '/') {
        sign = -1;
      } else if (c == '*' || c == '.') {
        sign = 1;
      } else {
        return result;
      }
      ++pos_;
    }
  }

  // term := name | 'sqrt(' product ')' | '(' product ')'
  Parsed parse_term() {
    skip_spaces();
    if (text_.substr(pos_, 5) == "sqrt(") {
      pos_ += 5;
      Parsed inner = parse_product();
      expect(')');
      Parsed root;
      accumulate(root, inner, 1);
      return root;
    }
    if (peek() == '(') {
      ++pos_;
      Parsed inner = parse_product();
      expect(')');
      return inner;
    }
    const std::size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '/' && text_[pos_] != '*' && text_[pos_] != '^' &&
           text_[pos_] != '(' && text_[pos_] != ')' && text_[pos_] != ' ' &&
           !(text_[pos_] == '.' && pos_ > start)) {
      ++pos_;
    }
    if (pos_ == start) fail("expected a unit name");
    return named(text_.substr(start, pos_ - start), text_);
  }

  // Whole powers, or halves written 0.5 / -0.5 / 1.5; returned in halves (2 for a power of 1).
  int parse_power_in_halves() {
    skip_spaces();
    const std::size_t start = pos_;
    if (peek() == '-' || peek() == '+') ++pos_;
    while (pos_ < text_.size() && (std::isdigit(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '.')) ++pos_;
    const std::string number(text_.substr(start, pos_ - start));
    double value = 0.0;
    try {
      value = std::stod(number);
    } catch (const std::exception&) {
      fail("expected a power after '^'");
    }
    const double halves = 2.0 * value;
    if (halves != std::round(halves)) fail("powers must be whole or half numbers");
    return static_cast<int>(halves);
  }

  void expect(char c) {
    skip_spaces();
    if (peek() != c) fail(std::string("expected '") + c + "'");
    ++pos_;
  }
  char peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }
  void skip_spaces() {
    while (pos_ < text_.size() && text_[pos_] == ' ') ++pos_;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw Error("cannot parse unit '" + std::string(text_) + "' at character " + std::to_string(pos_ + 1) +
                ": " + what);
  }

  std::string_view text_;
  std::size_t pos_ = 0;
};

}  // namespace

std::string Dimension::to_string() const {
  static constexpr std::array<const char*, kBaseCount> names = {"angle", "time",    "length",  "mass",
                                                                "temperature", "voltage", "current", "count"};
  std::string text;
  for (std::size_t i = 0; i < half_powers.size(); ++i) {
    if (half_powers[i] == 0) continue;
    if (!text.empty()) text += "*";
    text += names[i];
    if (half_powers[i] != 2) {
      text += "^";
      text += half_powers[i] % 2 == 0 ? std::to_string(half_powers[i] / 2)
                                      : std::to_string(half_powers[i] / 2.0).substr(0, 4);
    }
  }
  return text.empty() ? "dimensionless" : text;
}

Unit Unit::parse(std::string_view text) {
  std::size_t begin = 0;
  std::size_t end = text.size();
  while (begin < end && std::isspace(static_cast<unsigned char>(text[begin]))) ++begin;
  while (end > begin && std::isspace(static_cast<unsigned char>(text[end - 1]))) --end;
  const std::string_view trimmed = text.substr(begin, end - begin);
  if (trimmed.empty()) throw Error("empty unit string");
  Parsed parsed = UnitParser(trimmed).parse_all();
  Unit unit;
  unit.symbol_ = std::string(trimmed);
  unit.factor_ = parsed.factor;
  unit.dimension_ = parsed.dimension;
  return unit;
}

double convert(double value, const Unit& from, const Unit& to) {
  if (from.dimension() != to.dimension()) {
    throw Error("cannot convert '" + from.symbol() + "' (" + from.dimension().to_string() + ") to '" +
                to.symbol() + "' (" + to.dimension().to_string() + ")");
  }
  // A bare temperature (degC, K) may be absolute (-40 degC is 233.15 K) or a difference (a 10 degC
  // step is 10 K), and a unit string cannot tell which: converting one temperature unit into another
  // is refused rather than guessed. Temperature within a compound unit (ppm/degC, deg/h/degC, degC/s)
  // is a difference and converts by its factor.
  Dimension bare_temperature;
  bare_temperature.half_powers[Dimension::kTemperature] = 2;
  // One temperature scale however spelt (°C, DEGC): only a change of scale is refused.
  const auto celsius_as_degC = [](const std::string& symbol) {
    return symbol == "°C" || lower(symbol) == "degc" ? std::string("degC") : symbol;
  };
  if (from.dimension() == bare_temperature && celsius_as_degC(from.symbol()) != celsius_as_degC(to.symbol())) {
    throw Error("cannot convert the temperature '" + from.symbol() + "' to '" + to.symbol() +
                "': an absolute temperature needs an offset a difference does not, and the unit cannot say which; "
                "give the value in '" + from.symbol() + "', the figure's unit");
  }
  return value * (from.factor() / to.factor());
}

double convert(double value, std::string_view from, std::string_view to) {
  return convert(value, Unit::parse(from), Unit::parse(to));
}

bool converts(std::string_view from, std::string_view to) {
  try {
    convert(1.0, from, to);
    return true;
  } catch (const Error&) {
    return false;
  }
}

bool counts_pulses(std::string_view unit) {
  std::string lower(unit);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  return lower == "pulse" || lower == "pulses";
}

std::string unit_suffix(const std::string& unit) { return unit.empty() || unit == "1" ? "" : " " + unit; }

bool same_unit(std::string_view first, std::string_view second) {
  if (first == second) return true;
  try {
    return std::abs(convert(1.0, first, second) - 1.0) <= 1e-12;
  } catch (const Error&) {
    return false;
  }
}

}  // namespace inertest

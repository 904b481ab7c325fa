// Units of measure: parsing of unit strings and conversion between units of one dimension.
//
// Every quantity in inertest carries its unit. Inside the library angles are in rad and rates in
// rad/s; units are converted at the edges with convert(). A unit string is a product of named
// units with optional integer or half-integer powers, e.g. "deg/h", "deg/sqrt(h)", "deg/h/g^2",
// "pulse/s", "mV", "ppm", "arcsec". "g" is the standard acceleration of gravity (9.80665 m/s^2),
// as in drift coefficients in deg/h/g. An unknown name is an Error, never a guess.
#pragma once

#include <array>
#include <string>
#include <string_view>

namespace inertest {

// Exponents of the base dimensions, in halves (2 means power 1), so that deg/sqrt(h) is exact.
struct Dimension {
  enum Base { kAngle, kTime, kLength, kMass, kTemperature, kVoltage, kCurrent, kCount, kBaseCount };
  std::array<int, kBaseCount> half_powers{};

  bool operator==(const Dimension&) const = default;
  std::string to_string() const;
};

class Unit {
 public:
  // Parses a unit string; throws inertest::Error naming the unknown part.
  static Unit parse(std::string_view text);

  // The dimensionless unit "1".
  Unit() = default;

  const std::string& symbol() const { return symbol_; }
  const Dimension& dimension() const { return dimension_; }
  // Value of 1 of this unit in the coherent SI-like base (rad, s, m, kg, K, V, A, count).
  double factor() const { return factor_; }
  bool is_dimensionless() const { return dimension_ == Dimension{}; }

 private:
  std::string symbol_ = "1";
  double factor_ = 1.0;
  Dimension dimension_;
};

// Converts value from one unit to another of the same dimension; throws Error otherwise.
double convert(double value, const Unit& from, const Unit& to);
double convert(double value, std::string_view from, std::string_view to);

// The same unit: the same text, or units that convert 1 to 1 ("deg/s" and "°/s"); false for units
// of other dimensions and for a unit inertest does not know.
bool same_unit(std::string_view first, std::string_view second);

// Whether a value in `from` converts to `to` (convert would not throw): false for units of other
// dimensions, for two bare temperature scales (degC, K) and for a unit inertest does not know.
bool converts(std::string_view from, std::string_view to);

// Whether `unit` names pulses counted (pulse or pulses, in any case): a counter's accumulation over
// each sample interval, a rate only per interval. Not count or LSB, which are levels (an ADC's reading).
bool counts_pulses(std::string_view unit);
// A unit as it follows a number in a message: " deg/h", and nothing for "1" (a plain number) or "".
std::string unit_suffix(const std::string& unit);

// Physical constants used across the procedures, each with its source.
namespace constants {
inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDegree = kPi / 180.0;             // rad per deg
inline constexpr double kArcsecond = kDegree / 3600.0;     // rad per arcsec
inline constexpr double kStandardGravity = 9.80665;        // m/s^2, CGPM 1901
// Earth rotation rate relative to the fixed stars, 7.2921150e-5 rad/s (IERS; WGS 84 uses
// 7.292115e-5). In deg/h: 15.041067 deg/h.
inline constexpr double kEarthRate = 7.2921150e-5;         // rad/s
inline constexpr double kAbsoluteZeroDegC = -273.15;       // 0 K, degC (SI: T/K = t/degC + 273.15)
}  // namespace constants

}  // namespace inertest

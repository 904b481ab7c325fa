#include "inertest/core/units.h"

#include <gtest/gtest.h>

#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

struct ConversionCase {
  const char* from;
  const char* to;
  double value;
  double expected;
};

class UnitConversion : public ::testing::TestWithParam<ConversionCase> {};

TEST_P(UnitConversion, MatchesHandComputedFactor) {
  const auto& c = GetParam();
  EXPECT_NEAR_RELATIVE(convert(c.value, c.from, c.to), c.expected, 1e-14);
}

constexpr double kPi = constants::kPi;

INSTANTIATE_TEST_SUITE_P(
    Units, UnitConversion,
    ::testing::Values(ConversionCase{"deg/s", "deg/h", 1.0, 3600.0}, ConversionCase{"deg/h", "rad/s", 3600.0, kPi / 180.0},
                      ConversionCase{"rad", "arcsec", kPi / 180.0, 3600.0},
                      // 1 deg/sqrt(h) = 60 deg/h * sqrt(s)  (GJB 2426A 5.12.5: RWC units)
                      ConversionCase{"deg/sqrt(h)", "deg/h*sqrt(s)", 1.0, 60.0},
                      ConversionCase{"deg/h/sqrt(h)", "deg/h^1.5", 2.0, 2.0}, ConversionCase{"ppm", "%", 1e4, 1.0},
                      ConversionCase{"g", "m/s^2", 1.0, 9.80665}, ConversionCase{"mV", "V", 1500.0, 1.5},
                      ConversionCase{"Hz", "1/s", 10.0, 10.0}, ConversionCase{"kHz", "Hz", 2.0, 2000.0},
                      ConversionCase{"pulse/s/(deg/s)", "pulse/deg", 4.0, 4.0},
                      ConversionCase{"Mohm", "ohm", 2.0, 2e6}, ConversionCase{"deg/h/g^2", "deg/h/g/g", 1.0, 1.0},
                      ConversionCase{"arcmin", "arcsec", 1.0, 60.0}, ConversionCase{"rev", "deg", 1.0, 360.0},
                      // as loggers and data sheets write them (HDF5 units, TDMS unit_string, headers)
                      ConversionCase{"DEG/S", "deg/h", 1.0, 3600.0}, ConversionCase{"Deg/s", "deg/s", 1.0, 1.0},
                      ConversionCase{"degrees/second", "deg/s", 1.0, 1.0}, ConversionCase{"deg/hour", "deg/h", 1.0, 1.0},
                      ConversionCase{"rpm", "deg/s", 1.0, 6.0}, ConversionCase{"dps", "deg/h", 1.0, 3600.0},
                      ConversionCase{"dph", "deg/s", 3600.0, 1.0}, ConversionCase{"DPH", "deg/h", 1.0, 1.0},
                      ConversionCase{"pulses/s", "pulse/s", 2.0, 2.0}, ConversionCase{"counts", "count", 1.0, 1.0},
                      ConversionCase{"cnt/s", "count/s", 1.0, 1.0}, ConversionCase{"lsb", "LSB", 1.0, 1.0},
                      ConversionCase{"m/s2", "m/s^2", 1.0, 1.0}, ConversionCase{"Volts", "mV", 1.0, 1000.0},
                      // a bond's milliohms are no megohms (case folding had read mOhm as Mohm, 1e9 off)
                      ConversionCase{"mOhm", "ohm", 5.0, 5e-3}, ConversionCase{"KHZ", "Hz", 1.0, 1000.0},
                      ConversionCase{"DEGC", "degC", 20.0, 20.0},
                      // a power supply's currents and a pickoff's voltages, with the micro sign or the Greek mu
                      ConversionCase{"µA", "mA", 250.0, 0.25}, ConversionCase{"μA", "uA", 1.0, 1.0},
                      ConversionCase{"µV", "V", 2e6, 2.0}, ConversionCase{"μV/(deg/s)", "mV/(deg/s)", 5.0, 5e-3}));

TEST(Units, IncompatibleDimensionsAreAnError) {
  EXPECT_THROW(convert(1.0, "deg/h", "deg"), Error);
  EXPECT_THROW(convert(1.0, "V", "pulse"), Error);
  try {
    convert(1.0, "deg/h", "V");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("cannot convert 'deg/h'"));
  }
}

// -40 degC is 233.15 K, a 10 degC step is 10 K: a bare temperature unit cannot say which, so one
// is never converted into another (a limit in K on a figure in degC read -40 degC as -40 K); in a
// compound unit the temperature is a difference (a sensitivity per degree) and converts.
TEST(Units, BareTemperaturesAreNotConvertedCompoundOnesAre) {
  try {
    convert(-40.0, "degC", "K");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("cannot convert the temperature 'degC' to 'K'"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("give the value in 'degC'"));
  }
  EXPECT_THROW(convert(290.0, "K", "degC"), Error);
  EXPECT_EQ(convert(-40.0, "degC", "degC"), -40.0);
  EXPECT_EQ(convert(3.0, "ppm/degC", "ppm/K"), 3.0);
  EXPECT_EQ(convert(3.0, "deg/h/K", "deg/h/degC"), 3.0);
  EXPECT_EQ(convert(0.5, "degC/s", "K/s"), 0.5);
  EXPECT_EQ(convert(2.0, "degC^2", "K^2"), 2.0);
  // °C, as the report prints it, is degC (a unit copied from a report into a plan was refused).
  EXPECT_EQ(convert(-40.0, "°C", "degC"), -40.0);
  EXPECT_EQ(convert(1.5, "ppm/°C", "ppm/degC"), 1.5);
  EXPECT_THROW(convert(-40.0, "°C", "K"), Error);
}

TEST(Units, UnknownNamesAreAnErrorNotAGuess) {
  // Capitals are read in another case only all in capitals with two letters or more, and not where
  // two units share the spelling (MOHM: milli- or megohm); one capital may be another unit (S, G, k).
  for (const char* text : {"degs/h", "furlong", "deg//h", "", "deg^x", "sqrt(h", "deg/", "s22", "x2", "MOHM", "G",
                           "k", "S", "mS", "Gs"}) {
    EXPECT_THROW(Unit::parse(text), Error) << text;
  }
  try {
    Unit::parse("deg/fortnight");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("unknown unit 'fortnight'"));
  }
  try {
    Unit::parse("MOHM");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("unit 'MOHM' in 'MOHM' is ambiguous in capitals: write "));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("Mohm"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("mohm"));
  }
}

TEST(Units, DimensionsOfDerivedUnits) {
  EXPECT_TRUE(Unit::parse("ppm").is_dimensionless());
  EXPECT_TRUE(Unit::parse("1").is_dimensionless());
  EXPECT_EQ(Unit::parse("deg/sqrt(h)").dimension(), Unit::parse("rad/s^0.5").dimension());
  EXPECT_EQ(Unit::parse("W").dimension(), Unit::parse("V*A").dimension());
  EXPECT_EQ(Unit::parse(" deg/h ").symbol(), "deg/h");
}

}  // namespace
}  // namespace inertest

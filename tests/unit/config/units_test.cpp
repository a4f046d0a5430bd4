#include "mechsim/config/units.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace mechsim::config {
namespace {

constexpr double kPi = std::numbers::pi;

// A conversion is a handful of double multiplications (prefix, unit factor, exponent), each
// off by at most an ulp (2.2e-16 relative); 1e-13 leaves room for that and is still many
// orders below any wrong factor (the closest pair, 1 vs 2*pi/60*10, differs by 5 %).
constexpr double kRelTol = 1e-13;

void expect_si(const char* text, Dimension d, double expected_si) {
  SCOPED_TRACE(text);
  const Quantity q = parse_quantity(text);
  EXPECT_TRUE(q.has_unit);
  EXPECT_EQ(q.dimension, d) << "got " << base_units(q.dimension) << ", want " << base_units(d);
  EXPECT_NEAR(q.value_si, expected_si, kRelTol * std::abs(expected_si));
}

std::string message_of(std::string_view text, Dimension expected) {
  try {
    parse_quantity_as(text, expected);
  } catch (const UnitError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Units, BareNumberIsSiInTheExpectedDimension) {
  const Quantity q = parse_quantity("25");
  EXPECT_FALSE(q.has_unit);
  EXPECT_EQ(q.value_si, 25.0);
  EXPECT_EQ(parse_quantity_as("0.025", dim::length), 0.025);
  EXPECT_EQ(parse_quantity_as("-1.5e-3", dim::mass), -1.5e-3);
  EXPECT_EQ(parse_quantity_as("+2", dim::torque), 2.0);
  EXPECT_EQ(parse_quantity_as(".5", dim::angle), 0.5);
  EXPECT_EQ(parse_quantity_as("  7  ", dim::time), 7.0);
}

TEST(Units, EachUnit) {
  expect_si("2 m", dim::length, 2.0);
  expect_si("2 g", dim::mass, 2e-3);
  expect_si("2 s", dim::time, 2.0);
  expect_si("2 min", dim::time, 120.0);
  expect_si("2 h", dim::time, 7200.0);
  expect_si("2 rad", dim::angle, 2.0);
  expect_si("45 deg", dim::angle, kPi / 4);
  expect_si("45 \u00B0", dim::angle, kPi / 4);
  expect_si("45\u00B0", dim::angle, kPi / 4);
  expect_si("2 rev", dim::angle, 4 * kPi);
  expect_si("30 rpm", dim::angular_velocity, kPi);
  expect_si("2 N", dim::force, 2.0);
  expect_si("2 Nm", dim::torque, 2.0);
  expect_si("2 Pa", dim::pressure, 2.0);
  expect_si("2 J", dim::energy, 2.0);
  expect_si("2 W", dim::power, 2.0);
  expect_si("2 V", dim::voltage, 2.0);
  expect_si("2 A", dim::current, 2.0);
  expect_si("2 ohm", dim::resistance, 2.0);
  expect_si("2 Ohm", dim::resistance, 2.0);
  expect_si("2 \u03A9", dim::resistance, 2.0);
  expect_si("2 H", dim::inductance, 2.0);
  expect_si("2 Hz", dim::frequency, 2.0);
  expect_si("30 %", dim::dimensionless, 0.3);
  expect_si("30%", dim::dimensionless, 0.3);
}

TEST(Units, Prefixes) {
  expect_si("3 nm", dim::length, 3e-9);
  expect_si("3 um", dim::length, 3e-6);
  expect_si("3 \u00B5m", dim::length, 3e-6);
  expect_si("3 mm", dim::length, 3e-3);
  expect_si("3 cm", dim::length, 3e-2);
  expect_si("3 km", dim::length, 3e3);
  expect_si("3 kg", dim::mass, 3.0);
  expect_si("3 mg", dim::mass, 3e-6);
  expect_si("3 ms", dim::time, 3e-3);
  expect_si("3 us", dim::time, 3e-6);
  expect_si("3 kN", dim::force, 3e3);
  expect_si("3 MPa", dim::pressure, 3e6);
  expect_si("3 GPa", dim::pressure, 3e9);
  expect_si("3 kJ", dim::energy, 3e3);
  expect_si("3 kW", dim::power, 3e3);
  expect_si("3 mV", dim::voltage, 3e-3);
  expect_si("3 mA", dim::current, 3e-3);
  expect_si("3 kohm", dim::resistance, 3e3);
  expect_si("3 M\u03A9", dim::resistance, 3e6);
  expect_si("3 mH", dim::inductance, 3e-3);
  expect_si("3 kHz", dim::frequency, 3e3);
}

TEST(Units, AmbiguousSymbolsResolveAsDocumented) {
  expect_si("1 m", dim::length, 1.0);    // metre, not a bare prefix
  expect_si("1 mm", dim::length, 1e-3);  // millimetre
  expect_si("1 min", dim::time, 60.0);   // minute, not milli-"in"
  expect_si("1 ms", dim::time, 1e-3);    // millisecond, not metre-second
  expect_si("1 m s", dim::length * dim::time, 1.0);
  expect_si("1 mHz", dim::frequency, 1e-3);
  expect_si("1 Nm", dim::torque, 1.0);   // newton metre ...
  expect_si("1 nm", dim::length, 1e-9);  // ... nanometre
  expect_si("1 h", dim::time, 3600.0);   // hour, not a prefix
}

TEST(Units, CompoundUnitsAndExponents) {
  expect_si("9 N/mm", dim::stiffness, 9e3);
  expect_si("500 N m/rad", dim::torsional_stiffness, 500.0);
  expect_si("0.2 N m s/rad", dim::rotational_damping, 0.2);
  expect_si("0.02 kg m^2", dim::inertia, 0.02);
  expect_si("20 N s/m", dim::viscous_damping, 20.0);
  expect_si("100 mm^2/s", dim::kinematic_viscosity, 1e-4);
  expect_si("9.81 m/s^2", dim::acceleration, 9.81);
  expect_si("9.81 m s^-2", dim::acceleration, 9.81);
  expect_si("9.81 m/s/s", dim::acceleration, 9.81);  // every factor after "/" divides
  expect_si("1500 N/mm\u00B2", dim::pressure, 1.5e9);
  expect_si("7850 kg/m\u00B3", dim::density, 7850.0);
  expect_si("7.85 g/cm^3", dim::density, 7850.0);
  expect_si("0.05 V s/rad", dim::back_emf_constant, 0.05);
  expect_si("0.05 N m/A", dim::torque_constant, 0.05);
  expect_si("2 N*m", dim::torque, 2.0);
  expect_si("2 N\u00B7m", dim::torque, 2.0);
  expect_si("2 kN*mm", dim::torque, 2.0);
  expect_si("3 rev/s", dim::angular_velocity, 6 * kPi);
  expect_si("90 deg/s", dim::angular_velocity, kPi / 2);
  expect_si("10 rad/s^2", dim::angular_acceleration, 10.0);
  expect_si("120 1/min", dim::frequency, 2.0);
  expect_si("0.5 m/s", dim::velocity, 0.5);
  expect_si("0.05 Pa s", dim::dynamic_viscosity, 0.05);
  expect_si("25mm", dim::length, 0.025);
  expect_si("1 m^9/m^9", dim::dimensionless, 1.0);  // the largest exponents accepted
  expect_si("1 m^-9 m^9", dim::dimensionless, 1.0);
}

TEST(Units, ExponentsAreBounded) {
  // A product of many factors stays bounded too: 12 factors of m^9 reach 108 > 99.
  std::string text = "1";
  for (int i = 0; i < 12; ++i) text += " m^9";
  EXPECT_THROW(parse_quantity(text), UnitError);
  try {
    parse_quantity("1 m^12");
    FAIL() << "no error";
  } catch (const UnitError& e) {
    EXPECT_STREQ(e.what(), "cannot read '1 m^12' as a quantity: the exponent of 'm' must be an integer from -9 to 9");
  }
}

TEST(Units, AngleIsItsOwnDimension) {
  EXPECT_EQ(message_of("45 deg", dim::length), "expected a length, e.g. '25 mm', got '45 deg'");
  EXPECT_NE(message_of("50 Hz", dim::angular_velocity).find("Hz is a frequency"),
            std::string::npos);
  EXPECT_THROW(parse_quantity_as("30 rpm", dim::frequency), UnitError);
  EXPECT_THROW(parse_quantity_as("0.1 rad", dim::dimensionless), UnitError);
  // Torque and torsional stiffness differ only by the radian.
  EXPECT_THROW(parse_quantity_as("500 N m", dim::torsional_stiffness), UnitError);
  EXPECT_NEAR(parse_quantity_as("30 rpm", dim::angular_velocity), kPi, kRelTol * kPi);
}

TEST(Units, NamedDimensionsHaveTheDocumentedExponents) {
  // Order: m, kg, s, A, rad.
  EXPECT_EQ(dim::voltage, (Dimension{{2, 1, -3, -1, 0}}));
  EXPECT_EQ(dim::resistance, (Dimension{{2, 1, -3, -2, 0}}));
  EXPECT_EQ(dim::inductance, (Dimension{{2, 1, -2, -2, 0}}));
  EXPECT_EQ(dim::back_emf_constant, (Dimension{{2, 1, -2, -1, -1}}));
  EXPECT_EQ(dim::tacho_constant, dim::back_emf_constant);
  EXPECT_EQ(dim::torque_constant, (Dimension{{2, 1, -2, -1, 0}}));
  EXPECT_EQ(dim::rotational_damping, (Dimension{{2, 1, -1, 0, -1}}));
  EXPECT_EQ(dim::pressure, (Dimension{{-1, 1, -2, 0, 0}}));
  EXPECT_EQ(dim::frequency, (Dimension{{0, 0, -1, 0, 0}}));
}

TEST(Units, Refusals) {
  const char* bad[] = {
      "",           // empty
      "   ",        // blank
      "abc",        // no number
      "mm",         // unit without a number
      "25 kgg",     // unknown unit
      "5 furlong",  // unknown unit
      "25 mm extra",
      "1,5 mm",  // decimal comma
      "inf",     // not a finite number
      "nan",
      "1e999 m",     // overflows
      "1e300 km^3",  // finite number, overflowing SI value
      "3 m^x",       // exponent not an integer
      "1 s^2147483647 s",   // exponents beyond +-9 (their int sum overflowed: UB, found by scene_fuzz)
      "1 1/m^-2147483648",  // (negating it overflowed)
      "1 m^10",
      "1 kg^-10",
      "3 m^",
      "3 N/",            // nothing after the slash
      "3 ^2",            // exponent without a unit
      "0.05 V/(rad/s)",  // parentheses
      "3 mrad",          // no prefixes on rad
      "3 kmin",          // nor on min
  };
  for (const char* text : bad) {
    SCOPED_TRACE(text);
    EXPECT_THROW(parse_quantity(text), UnitError);
  }
}

TEST(Units, RefusalMessagesSayWhatWasExpected) {
  EXPECT_EQ(message_of("25 mm", dim::mass), "expected a mass, e.g. '25 kg', got '25 mm'");
  EXPECT_EQ(message_of("25 kgg", dim::mass),
            "expected a mass, e.g. '25 kg', got '25 kgg' (unknown unit 'kgg')");
  EXPECT_EQ(message_of("", dim::length),
            "expected a length, e.g. '25 mm', got '' (the value is empty)");
  EXPECT_NE(message_of("3 m2", dim::pressure).find("write exponents with '^'"), std::string::npos);
  try {
    parse_quantity("25 kgg");
    FAIL() << "no error";
  } catch (const UnitError& e) {
    EXPECT_STREQ(e.what(), "cannot read '25 kgg' as a quantity: unknown unit 'kgg'");
  }
}

TEST(Units, Describe) {
  EXPECT_EQ(describe(dim::length), "a length, e.g. '25 mm'");
  EXPECT_EQ(describe(dim::stiffness), "a stiffness, e.g. '9 N/mm'");
  // Every example in a description must itself parse to the described dimension.
  const Dimension named[] = {dim::dimensionless,
                             dim::length,
                             dim::mass,
                             dim::time,
                             dim::current,
                             dim::angle,
                             dim::angular_velocity,
                             dim::angular_acceleration,
                             dim::velocity,
                             dim::acceleration,
                             dim::frequency,
                             dim::force,
                             dim::torque,
                             dim::power,
                             dim::stiffness,
                             dim::torsional_stiffness,
                             dim::inertia,
                             dim::viscous_damping,
                             dim::rotational_damping,
                             dim::voltage,
                             dim::resistance,
                             dim::inductance,
                             dim::pressure,
                             dim::density,
                             dim::dynamic_viscosity,
                             dim::kinematic_viscosity,
                             dim::back_emf_constant,
                             dim::torque_constant};
  for (const Dimension& d : named) {
    const std::string text = describe(d);
    SCOPED_TRACE(text);
    const std::size_t open = text.find("e.g. '");
    ASSERT_NE(open, std::string::npos);
    const std::size_t close = text.find('\'', open + 6);
    const std::string example = text.substr(open + 6, close - open - 6);
    EXPECT_NO_THROW(parse_quantity_as(example, d)) << example;
  }
  // Unnamed dimensions are spelled out in base units.
  EXPECT_EQ(describe(dim::length.pow(3) / dim::time), "a quantity in m^3 s^-1");
  EXPECT_EQ(base_units(dim::dimensionless), "1");
}

}  // namespace
}  // namespace mechsim::config

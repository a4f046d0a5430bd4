// Quantities with units in scene files: "25 mm", "30 rpm", "9 N/mm", "0.02 kg m^2".
//
// Grammar:   <number> [<unit expression>]
//   number        a decimal floating-point literal ("25", "-1.5", "2e-3", ".5")
//   unit expr     factors separated by spaces, '*' or '·'; a '/' puts every following
//                 factor in the denominator ("N m s/rad", "mm^2/s", "m/s^2", "1/min");
//                 a factor is a unit with an optional exponent "^n" (n may be negative)
//                 or "²"/"³". Parentheses are not accepted: write "V s/rad", not "V/(rad/s)".
//   units         m, g, s, min, h, rad, deg (°), rev, rpm (= rev/min), N, Nm (= N m), Pa,
//                 J, W, V, A, ohm (Ohm, Ω), H (henry), Hz, % (= 0.01), and the factor 1.
//   prefixes      n, u (µ), m, c, k, M, G on m, g, s, N, Pa, J, W, V, A, ohm, H, Hz
//                 ("mm", "kN", "MPa", "mH", "ms", "kHz"). Whole symbols are matched first,
//                 so "m" is the metre, "min" the minute and "mm" the millimetre.
// A bare number carries no unit and is read as SI in whatever dimension is expected.
//
// Dimensions are integer exponents over (m, kg, s, A, rad). The plane angle is kept as a
// base dimension of its own (SI treats it as dimensionless) so that input mistakes are
// caught: "45 deg" is refused where a length is expected, "30 rpm" is an angular velocity
// (rad/s) while "50 Hz" is a frequency (1/s) and is refused as a shaft speed. Numeric
// values are plain SI with 1 rad = 1, so nothing changes inside the models; the only cost
// is that rad-bearing dimensions do not combine as in textbooks (torque "N m" and
// torsional stiffness "N m/rad" differ; "V s/rad" (back-EMF, tacho) and "N m/A"
// (torque constant) differ although they are equal in SI).
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <string_view>

namespace mechsim::config {

// Exponents over the base units, in this order.
enum BaseUnit { kMetre = 0, kKilogram, kSecond, kAmpere, kRadian, kNumBaseUnits };

struct Dimension {
  std::array<int, kNumBaseUnits> exp{};  // m, kg, s, A, rad

  friend constexpr bool operator==(const Dimension&, const Dimension&) = default;
  friend constexpr Dimension operator*(const Dimension& a, const Dimension& b) {
    Dimension r;
    for (int i = 0; i < kNumBaseUnits; ++i) r.exp[i] = a.exp[i] + b.exp[i];
    return r;
  }
  friend constexpr Dimension operator/(const Dimension& a, const Dimension& b) {
    Dimension r;
    for (int i = 0; i < kNumBaseUnits; ++i) r.exp[i] = a.exp[i] - b.exp[i];
    return r;
  }
  constexpr Dimension pow(int n) const {
    Dimension r;
    for (int i = 0; i < kNumBaseUnits; ++i) r.exp[i] = exp[i] * n;
    return r;
  }
};

// Named dimensions (exponents of m, kg, s, A, rad).
namespace dim {
inline constexpr Dimension dimensionless{{0, 0, 0, 0, 0}};
inline constexpr Dimension length{{1, 0, 0, 0, 0}};
inline constexpr Dimension mass{{0, 1, 0, 0, 0}};
inline constexpr Dimension time{{0, 0, 1, 0, 0}};
inline constexpr Dimension current{{0, 0, 0, 1, 0}};
inline constexpr Dimension angle{{0, 0, 0, 0, 1}};
inline constexpr Dimension angular_velocity = angle / time;
inline constexpr Dimension angular_acceleration = angle / time.pow(2);
inline constexpr Dimension velocity = length / time;
inline constexpr Dimension acceleration = length / time.pow(2);
inline constexpr Dimension frequency = dimensionless / time;
inline constexpr Dimension force = mass * acceleration;                 // N
inline constexpr Dimension torque = force * length;                     // N m
inline constexpr Dimension energy = force * length;                     // J (= torque)
inline constexpr Dimension power = energy / time;                       // W
inline constexpr Dimension stiffness = force / length;                  // N/m
inline constexpr Dimension torsional_stiffness = torque / angle;        // N m/rad
inline constexpr Dimension inertia = mass * length.pow(2);              // kg m^2
inline constexpr Dimension viscous_damping = force * time / length;     // N s/m
inline constexpr Dimension rotational_damping = torque * time / angle;  // N m s/rad
inline constexpr Dimension voltage = power / current;                   // V
inline constexpr Dimension resistance = voltage / current;              // ohm
inline constexpr Dimension inductance = voltage * time / current;       // H
inline constexpr Dimension pressure = force / length.pow(2);            // Pa (also stress)
inline constexpr Dimension density = mass / length.pow(3);              // kg/m^3
inline constexpr Dimension dynamic_viscosity = pressure * time;         // Pa s
inline constexpr Dimension kinematic_viscosity = length.pow(2) / time;  // m^2/s
inline constexpr Dimension back_emf_constant = voltage * time / angle;  // V s/rad
inline constexpr Dimension tacho_constant = back_emf_constant;          // V s/rad
inline constexpr Dimension torque_constant = torque / current;          // N m/A
}  // namespace dim

// A parse failure. what() reads as the tail of a configuration error, e.g.
// "expected a mass, e.g. '25 kg', got '25 mm'".
class UnitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Quantity {
  double value_si = 0.0;
  Dimension dimension;    // dimensionless for a bare number
  bool has_unit = false;  // false for a bare number (SI in whatever dimension is expected)
};

// Parses "<number> [<unit expression>]" into SI. Throws UnitError.
Quantity parse_quantity(std::string_view text);

// Parses and checks the dimension; a bare number is taken as SI in `expected`.
// Throws UnitError, e.g. "expected a mass, e.g. '25 kg', got '25 mm'".
double parse_quantity_as(std::string_view text, Dimension expected);

// A human name with an example, for messages: "a length, e.g. '25 mm'". Dimensions
// without a name are spelled out: "a quantity in m^2 kg s^-3".
std::string describe(Dimension d);

// The dimension in base units, e.g. "m kg s^-2" ("1" for dimensionless).
std::string base_units(Dimension d);

}  // namespace mechsim::config

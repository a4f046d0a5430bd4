#include "mechsim/config/units.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

namespace mechsim::config {
namespace {

// Why a text is not a quantity ("unknown unit 'kgg'"); the public functions wrap it into
// a UnitError that also says what was expected.
class Detail : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct UnitDef {
  std::string_view symbol;
  double factor;  // SI value of one unit
  Dimension dimension;
  bool takes_prefix;
};

// Whole symbols are looked up before prefix + symbol, so "min" is the minute and "m"
// the metre. No prefixed symbol below collides with an unprefixed one.
const UnitDef kUnits[] = {
    {"m", 1.0, dim::length, true},
    {"g", 1e-3, dim::mass, true},
    {"s", 1.0, dim::time, true},
    {"min", 60.0, dim::time, false},
    {"h", 3600.0, dim::time, false},
    {"rad", 1.0, dim::angle, false},
    {"deg", std::numbers::pi / 180.0, dim::angle, false},
    {"\u00B0", std::numbers::pi / 180.0, dim::angle, false},  // °
    {"rev", 2.0 * std::numbers::pi, dim::angle, false},
    {"rpm", 2.0 * std::numbers::pi / 60.0, dim::angular_velocity, false},
    {"N", 1.0, dim::force, true},
    {"Nm", 1.0, dim::torque, false},  // unambiguous: the nano prefix is a lower-case n
    {"Pa", 1.0, dim::pressure, true},
    {"J", 1.0, dim::energy, true},
    {"W", 1.0, dim::power, true},
    {"V", 1.0, dim::voltage, true},
    {"A", 1.0, dim::current, true},
    {"ohm", 1.0, dim::resistance, true},
    {"Ohm", 1.0, dim::resistance, true},
    {"\u03A9", 1.0, dim::resistance, true},  // Greek capital omega
    {"\u2126", 1.0, dim::resistance, true},  // ohm sign
    {"H", 1.0, dim::inductance, true},
    {"Hz", 1.0, dim::frequency, true},
    {"%", 0.01, dim::dimensionless, false},
    {"1", 1.0, dim::dimensionless, false},  // for "1/s", "1/min"
};

struct Prefix {
  std::string_view symbol;
  double factor;
};

const Prefix kPrefixes[] = {
    {"n", 1e-9},
    {"u", 1e-6},
    {"\u00B5", 1e-6},  // micro sign
    {"\u03BC", 1e-6},  // Greek mu
    {"m", 1e-3},
    {"c", 1e-2},
    {"k", 1e3},
    {"M", 1e6},
    {"G", 1e9},
};

struct Scaled {
  double factor;
  Dimension dimension;
};

std::optional<Scaled> lookup_unit(std::string_view symbol) {
  for (const UnitDef& u : kUnits) {
    if (u.symbol == symbol) return Scaled{u.factor, u.dimension};
  }
  for (const Prefix& p : kPrefixes) {
    if (symbol.size() <= p.symbol.size() || !symbol.starts_with(p.symbol)) continue;
    const std::string_view rest = symbol.substr(p.symbol.size());
    for (const UnitDef& u : kUnits) {
      if (u.takes_prefix && u.symbol == rest) return Scaled{p.factor * u.factor, u.dimension};
    }
  }
  return std::nullopt;
}

// Multi-byte (UTF-8) tokens that end a unit symbol.
constexpr std::string_view kMiddleDot = "\u00B7";
constexpr std::string_view kSuperscript2 = "\u00B2";
constexpr std::string_view kSuperscript3 = "\u00B3";

bool is_space(char c) { return c == ' ' || c == '\t'; }

bool ends_symbol(std::string_view rest) {
  const char c = rest.front();
  return is_space(c) || c == '*' || c == '/' || c == '^' || c == '(' || c == ')' ||
         rest.starts_with(kMiddleDot) || rest.starts_with(kSuperscript2) ||
         rest.starts_with(kSuperscript3);
}

// Reads "<number>" from the front of `s`; leaves the rest in `s`.
double read_number(std::string_view& s) {
  std::string_view digits = s;
  bool negative = false;
  if (!digits.empty() && (digits.front() == '+' || digits.front() == '-')) {
    negative = digits.front() == '-';
    digits.remove_prefix(1);
  }
  // from_chars would also take "inf"/"nan"; only decimal literals are values here.
  if (digits.empty() ||
      !(std::isdigit(static_cast<unsigned char>(digits.front())) || digits.front() == '.')) {
    throw Detail("it does not start with a number");
  }
  double value = 0.0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec == std::errc::result_out_of_range) throw Detail("the number is out of range");
  if (ec != std::errc()) throw Detail("it does not start with a number");
  s.remove_prefix(static_cast<std::size_t>(end - s.data()));
  return negative ? -value : value;
}

constexpr int kMaxExponent = 9;         // of one unit symbol
constexpr int kMaxDimensionExponent = 99;  // of the whole expression, e.g. "m m m ..."

// Reads an optional exponent after a unit symbol: "^n", "^-n", "²", "³".
int read_exponent(std::string_view& s, std::string_view symbol) {
  if (s.starts_with(kSuperscript2)) {
    s.remove_prefix(kSuperscript2.size());
    return 2;
  }
  if (s.starts_with(kSuperscript3)) {
    s.remove_prefix(kSuperscript3.size());
    return 3;
  }
  if (s.empty() || s.front() != '^') return 1;
  s.remove_prefix(1);
  int exponent = 0;
  const char* first = s.data();
  if (!s.empty() && s.front() == '+') ++first;  // from_chars takes '-' but not '+'
  const auto [end, ec] = std::from_chars(first, s.data() + s.size(), exponent);
  if (ec != std::errc()) {
    throw Detail("'^' after '" + std::string(symbol) + "' must be followed by an integer exponent");
  }
  s.remove_prefix(static_cast<std::size_t>(end - s.data()));
  // Physical units need small exponents; a bound keeps the dimension's int exponents (and
  // their products and sums below) far from overflow ("1 m^2147483647 m" was UB).
  if (exponent < -kMaxExponent || exponent > kMaxExponent) {
    throw Detail("the exponent of '" + std::string(symbol) + "' must be an integer from -" +
                 std::to_string(kMaxExponent) + " to " + std::to_string(kMaxExponent));
  }
  return exponent;
}

// Parses the whole text; failures throw Detail.
Quantity parse_or_throw_detail(std::string_view text) {
  std::string_view s = text;
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  if (s.empty()) throw Detail("the value is empty");

  Quantity q;
  q.value_si = read_number(s);
  bool in_denominator = false;
  bool factor_pending_after_slash = false;
  while (!s.empty()) {
    if (is_space(s.front()) || s.front() == '*') {
      s.remove_prefix(1);
      continue;
    }
    if (s.starts_with(kMiddleDot)) {
      s.remove_prefix(kMiddleDot.size());
      continue;
    }
    if (s.front() == '/') {
      in_denominator = true;
      factor_pending_after_slash = true;
      s.remove_prefix(1);
      continue;
    }
    if (s.front() == '(' || s.front() == ')') {
      throw Detail("parentheses are not accepted in units; write e.g. 'V s/rad'");
    }
    if (s.front() == '^' || s.starts_with(kSuperscript2) || s.starts_with(kSuperscript3)) {
      throw Detail("an exponent must follow a unit symbol");
    }
    std::size_t n = 0;
    while (n < s.size() && !ends_symbol(s.substr(n))) ++n;
    const std::string_view symbol = s.substr(0, n);
    s.remove_prefix(n);
    const std::optional<Scaled> unit = lookup_unit(symbol);
    if (!unit) {
      std::string detail = "unknown unit '" + std::string(symbol) + "'";
      if (std::isdigit(static_cast<unsigned char>(symbol.back())) && symbol.size() > 1) {
        detail += "; write exponents with '^', e.g. 'm^2'";
      }
      throw Detail(detail);
    }
    int exponent = read_exponent(s, symbol);
    if (in_denominator) exponent = -exponent;
    q.value_si *= std::pow(unit->factor, exponent);
    q.dimension = q.dimension * unit->dimension.pow(exponent);
    for (int e : q.dimension.exp)
      if (e < -kMaxDimensionExponent || e > kMaxDimensionExponent) throw Detail("the unit's exponents are out of range");
    q.has_unit = true;
    factor_pending_after_slash = false;
  }
  if (factor_pending_after_slash) throw Detail("'/' is not followed by a unit");
  if (!std::isfinite(q.value_si)) throw Detail("the value is out of range");
  return q;
}

struct NamedDimension {
  Dimension dimension;
  std::string_view description;
};

// Dimensions that are equal (torque and energy; back-EMF and tacho constants) share a line.
const NamedDimension kNamedDimensions[] = {
    {dim::dimensionless, "a plain number, e.g. '0.3' or '30 %'"},
    {dim::length, "a length, e.g. '25 mm'"},
    {dim::mass, "a mass, e.g. '25 kg'"},
    {dim::time, "a time, e.g. '10 ms'"},
    {dim::current, "a current, e.g. '2 A'"},
    {dim::angle, "an angle, e.g. '45 deg'"},
    {dim::angular_velocity, "an angular velocity, e.g. '30 rpm' or '3.1 rad/s'"},
    {dim::angular_acceleration, "an angular acceleration, e.g. '10 rad/s^2'"},
    {dim::velocity, "a velocity, e.g. '0.5 m/s'"},
    {dim::acceleration, "an acceleration, e.g. '9.81 m/s^2'"},
    {dim::frequency, "a frequency, e.g. '50 Hz'"},
    {dim::force, "a force, e.g. '200 N'"},
    {dim::torque, "a torque or energy, e.g. '2 N m' or '5 J'"},
    {dim::power, "a power, e.g. '750 W'"},
    {dim::stiffness, "a stiffness, e.g. '9 N/mm'"},
    {dim::torsional_stiffness, "a torsional stiffness, e.g. '500 N m/rad'"},
    {dim::inertia, "a moment of inertia, e.g. '0.02 kg m^2'"},
    {dim::viscous_damping, "a viscous damping, e.g. '20 N s/m'"},
    {dim::rotational_damping, "a rotational damping, e.g. '0.01 N m s/rad'"},
    {dim::voltage, "a voltage, e.g. '24 V'"},
    {dim::resistance, "a resistance, e.g. '1.2 ohm'"},
    {dim::inductance, "an inductance, e.g. '3 mH'"},
    {dim::pressure, "a pressure or stress, e.g. '2 MPa' or '1500 N/mm^2'"},
    {dim::density, "a density, e.g. '7850 kg/m^3'"},
    {dim::dynamic_viscosity, "a dynamic viscosity, e.g. '0.05 Pa s'"},
    {dim::kinematic_viscosity, "a kinematic viscosity, e.g. '100 mm^2/s'"},
    {dim::back_emf_constant, "a back-EMF or tacho constant, e.g. '0.05 V s/rad'"},
    {dim::torque_constant, "a torque constant, e.g. '0.05 N m/A'"},
};

}  // namespace

Quantity parse_quantity(std::string_view text) {
  try {
    return parse_or_throw_detail(text);
  } catch (const Detail& detail) {
    throw UnitError("cannot read '" + std::string(text) + "' as a quantity: " + detail.what());
  }
}

double parse_quantity_as(std::string_view text, Dimension expected) {
  Quantity q;
  try {
    q = parse_or_throw_detail(text);
  } catch (const Detail& detail) {
    throw UnitError("expected " + describe(expected) + ", got '" + std::string(text) + "' (" +
                    detail.what() + ")");
  }
  if (q.has_unit && q.dimension != expected) {
    std::string message = "expected " + describe(expected) + ", got '" + std::string(text) + "'";
    if (expected == dim::angular_velocity && q.dimension == dim::frequency) {
      message += " (Hz is a frequency; write a shaft speed in rpm, rev/s or rad/s)";
    }
    throw UnitError(message);
  }
  return q.value_si;
}

std::string base_units(Dimension d) {
  static constexpr std::string_view kNames[kNumBaseUnits] = {"m", "kg", "s", "A", "rad"};
  std::string out;
  for (int i = 0; i < kNumBaseUnits; ++i) {
    if (d.exp[i] == 0) continue;
    if (!out.empty()) out += ' ';
    out += kNames[i];
    if (d.exp[i] != 1) out += "^" + std::to_string(d.exp[i]);
  }
  return out.empty() ? "1" : out;
}

std::string describe(Dimension d) {
  for (const NamedDimension& named : kNamedDimensions) {
    if (named.dimension == d) return std::string(named.description);
  }
  return "a quantity in " + base_units(d);
}

}  // namespace mechsim::config

// The points of a design study: `--vary KEY=SPEC` parsed, and the designs made of them
// (a full grid, a Latin hypercube, plain random samples). Shared by `mechsim sweep` and the
// Python package (python/), so that both run the same points for the same arguments.
//
// SPEC is a list "a,b,c" (each entry any value the scene takes for KEY: "20 N", "hold",
// "1.5"), or a range of quantities "lo..hi:n" (n values, evenly spaced, both ends included)
// or "lo..hi:n:log" (evenly spaced in log, lo and hi > 0). A range's ends carry units as in
// scenes ("10 N..40 N:4", or the unit once: "10..40 N:4"); the values are written back in
// the unit of the range, so the scene checks their dimension as it checks its own.
// The random designs sample a range continuously over [lo, hi] (log: log-uniformly; n is
// not used; "lo..hi" and "lo..hi:log" need none) and a list by drawing its entries.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace mechsim::sweep {

// Bad --vary text, an empty range, a design that cannot be made: what() names the spec and
// what was expected.
class DesignError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct VarySpec {
  std::string key;                 // as written ("servo.position_gain", "time.step")
  bool is_range = false;
  std::vector<std::string> list;   // a list's entries
  double lo = 0, hi = 0;           // a range's ends, in the range's unit
  int n = 0;                       // a range's count (grid)
  bool log = false;
  std::string unit;                // the range's unit as written ("" = a bare number)
};

// Parses "KEY=SPEC". Throws DesignError.
VarySpec parse_vary(const std::string& text);

// A range's grid values, in its unit: exactly lo and hi at the ends.
std::vector<double> range_values(const VarySpec& spec);

// One value of a point: the text handed to the scene ("20 N"), and a number for tables and
// plots (the value in the range's unit; a list entry's leading number, NaN if it has none).
struct PointValue {
  std::string key;
  std::string text;
  double number = 0;
};

struct Point {
  int index = 0;
  std::vector<PointValue> values;  // one per VarySpec, in the order given
  // "KEY=TEXT" for each value, as --set takes them.
  std::vector<std::string> sets() const;
};

enum class Method { grid, lhs, random };
// "grid", "lhs", "random"; throws DesignError for another name.
Method parse_method(const std::string& name);
const char* to_string(Method m);

struct DesignOptions {
  Method method = Method::grid;
  int samples = 0;         // lhs/random: the number of points (> 0); grid: must be 0
  std::uint64_t seed = 1;  // lhs/random
};

// The design's points. grid: every combination, the last --vary changing fastest; lhs: in
// each key, each of the `samples` equal strata of [lo, hi] (of a list: of its entries)
// holds exactly one point, the strata paired at random; random: independent draws. The
// same specs, options and seed give the same points on every machine (own generator, no
// std:: distribution). Throws DesignError.
std::vector<Point> make_design(const std::vector<VarySpec>& specs, const DesignOptions& options);

// The number a list entry or a value starts with ("20 N" -> 20), NaN when none.
double leading_number(const std::string& text);

}  // namespace mechsim::sweep

#include "design.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>

#include "mechsim/config/units.h"
#include "text_format.h"

namespace mechsim::sweep {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

// "10 N" -> (10, "N"); "10" -> (10, ""). Throws DesignError when it does not start with a number.
std::pair<double, std::string> number_and_unit(const std::string& spec, const std::string& text) {
  const std::string t = trim(text);
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (t.empty() || end == t.c_str() || !std::isfinite(v))
    throw DesignError(spec + ": expected a quantity at '" + t + "', e.g. '10 N' or '2.5'");
  return {v, trim(std::string(end))};
}

// SI value of one `unit` (1 for a bare number). Throws DesignError naming the spec.
double unit_factor(const std::string& spec, const std::string& unit) {
  if (unit.empty()) return 1.0;
  try {
    return config::parse_quantity("1 " + unit).value_si;
  } catch (const config::UnitError& e) {
    throw DesignError(spec + ": unit '" + unit + "': " + e.what());
  }
}

config::Dimension dimension_of(const std::string& spec, const std::string& unit) {
  if (unit.empty()) return config::dim::dimensionless;
  try {
    return config::parse_quantity("1 " + unit).dimension;
  } catch (const config::UnitError& e) {
    throw DesignError(spec + ": unit '" + unit + "': " + e.what());
  }
}

// A value of a range as the scene gets it: 15 significant digits (every double of a range
// that was typed reads back as typed) and the range's unit.
PointValue range_point_value(const VarySpec& spec, double v) {
  std::string text = tools::fmt("%.15g", v);
  const double number = std::strtod(text.c_str(), nullptr);
  if (!spec.unit.empty()) text += " " + spec.unit;
  return {spec.key, text, number};
}

PointValue list_point_value(const VarySpec& spec, std::size_t i) {
  return {spec.key, spec.list[i], leading_number(spec.list[i])};
}

// splitmix64-seeded 64-bit Mersenne Twister (fully specified by the standard) and our own
// mapping to [0, 1) and to indices: the same points from the same seed with any library.
class Draws {
 public:
  explicit Draws(std::uint64_t seed) : engine_(seed) {}
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(engine_() % n); }

 private:
  std::mt19937_64 engine_;
};

// A value at u in [0, 1) of a spec's span: a range continuously (log: in log), a list by entry.
PointValue value_at(const VarySpec& spec, double u) {
  if (!spec.is_range) return list_point_value(spec, std::min(spec.list.size() - 1, static_cast<std::size_t>(u * spec.list.size())));
  const double v = spec.log ? std::exp(std::log(spec.lo) + u * (std::log(spec.hi) - std::log(spec.lo))) : spec.lo + u * (spec.hi - spec.lo);
  return range_point_value(spec, v);
}

}  // namespace

double leading_number(const std::string& text) {
  const std::string t = trim(text);
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  return end == t.c_str() ? std::numeric_limits<double>::quiet_NaN() : v;
}

VarySpec parse_vary(const std::string& text) {
  const auto eq = text.find('=');
  VarySpec spec;
  spec.key = trim(eq == std::string::npos ? "" : text.substr(0, eq));
  if (eq == std::string::npos || spec.key.empty())
    throw DesignError("--vary '" + text + "': expected KEY=SPEC, e.g. 'servo.position_gain=20..80 1/s:7' or 'follower.spring.preload=100 N,150 N'");
  const std::string body = trim(text.substr(eq + 1));
  const std::string where = "--vary " + spec.key;
  if (body.empty()) throw DesignError(where + ": no values (expected a list 'a,b' or a range 'lo..hi:n')");
  const auto dots = body.find("..");
  if (dots == std::string::npos) {
    std::size_t start = 0;
    while (true) {
      const auto comma = body.find(',', start);
      const std::string entry = trim(body.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
      if (entry.empty()) throw DesignError(where + ": an empty entry in the list '" + body + "'");
      spec.list.push_back(entry);
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    return spec;
  }
  spec.is_range = true;
  const std::string lo_text = body.substr(0, dots);
  std::string rest = body.substr(dots + 2);
  const auto colon = rest.find(':');
  const std::string hi_text = rest.substr(0, colon);
  std::string tail = colon == std::string::npos ? "" : rest.substr(colon + 1);
  if (trim(tail) == "log") {  // "lo..hi:log": a sampled range, no grid count
    spec.log = true;
  } else if (!tail.empty()) {
    const auto colon2 = tail.find(':');
    const std::string count = trim(tail.substr(0, colon2));
    const std::string scale = colon2 == std::string::npos ? "" : trim(tail.substr(colon2 + 1));
    char* end = nullptr;
    const long n = std::strtol(count.c_str(), &end, 10);
    if (count.empty() || *end != '\0') throw DesignError(where + ": expected a whole count after ':', got '" + count + "'");
    if (n < 2) throw DesignError(where + ": an empty range: lo..hi:" + count + " (a range needs n >= 2; one value is a list)");
    if (n > 1'000'000) throw DesignError(where + ": " + count + " values in one range (at most 1000000)");
    spec.n = static_cast<int>(n);
    if (scale == "log") spec.log = true;
    else if (!scale.empty()) throw DesignError(where + ": expected 'log' after the count, got '" + scale + "'");
  }
  auto [lo, lo_unit] = number_and_unit(where, lo_text);
  auto [hi, hi_unit] = number_and_unit(where, hi_text);
  // The unit once ("10..40 N") is the unit of both ends; two units are converted to the upper one's.
  spec.unit = hi_unit.empty() ? lo_unit : hi_unit;
  if (!lo_unit.empty() && lo_unit != spec.unit) {
    if (!(dimension_of(where, lo_unit) == dimension_of(where, spec.unit)))
      throw DesignError(where + ": the ends '" + trim(lo_text) + "' and '" + trim(hi_text) + "' are not of one dimension");
    lo = lo * unit_factor(where, lo_unit) / unit_factor(where, spec.unit);
  }
  unit_factor(where, spec.unit);  // a unit the scenes do not know is refused here, not per point
  spec.lo = lo;
  spec.hi = hi;
  if (lo == hi) throw DesignError(where + ": an empty range: both ends are " + trim(hi_text));
  if (spec.log && !(lo > 0 && hi > 0)) throw DesignError(where + ": a log range needs both ends > 0, got " + trim(lo_text) + ".." + trim(hi_text));
  return spec;
}

std::vector<double> range_values(const VarySpec& spec) {
  std::vector<double> v(static_cast<std::size_t>(spec.n));
  const double last = spec.n - 1;
  for (int i = 0; i < spec.n; ++i) {
    if (spec.log) {
      // Even in log10: a decade range gives its powers of ten exactly (pow(10, k) is exact).
      const double a = std::log10(spec.lo), b = std::log10(spec.hi);
      v[i] = std::pow(10.0, (a * (last - i) + b * i) / last);
    } else {
      v[i] = (spec.lo * (last - i) + spec.hi * i) / last;
    }
  }
  v.front() = spec.lo;
  v.back() = spec.hi;
  return v;
}

std::vector<std::string> Point::sets() const {
  std::vector<std::string> out;
  for (const auto& v : values) out.push_back(v.key + "=" + v.text);
  return out;
}

Method parse_method(const std::string& name) {
  if (name == "grid") return Method::grid;
  if (name == "lhs") return Method::lhs;
  if (name == "random") return Method::random;
  throw DesignError("--method: expected grid, lhs or random, got '" + name + "'");
}

const char* to_string(Method m) { return m == Method::grid ? "grid" : m == Method::lhs ? "lhs" : "random"; }

std::vector<Point> make_design(const std::vector<VarySpec>& specs, const DesignOptions& o) {
  if (specs.empty()) throw DesignError("no --vary: a sweep needs at least one KEY=SPEC");
  for (std::size_t i = 0; i < specs.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (specs[i].key == specs[j].key) throw DesignError("--vary " + specs[i].key + " is given twice");
  std::vector<Point> points;
  if (o.method == Method::grid) {
    if (o.samples != 0) throw DesignError("--samples is for --method lhs or random; a grid has the product of its --vary counts");
    std::vector<std::vector<PointValue>> axes;
    double total = 1;
    for (const auto& s : specs) {
      std::vector<PointValue> axis;
      if (!s.is_range) {
        for (std::size_t i = 0; i < s.list.size(); ++i) axis.push_back(list_point_value(s, i));
      } else {
        if (s.n == 0) throw DesignError("--vary " + s.key + ": a grid needs a count, e.g. 'lo..hi:5'");
        for (double v : range_values(s)) axis.push_back(range_point_value(s, v));
      }
      total *= static_cast<double>(axis.size());
      axes.push_back(std::move(axis));
    }
    if (total > 1e7) throw DesignError(tools::fmt("a grid of %.0f points (at most 10000000)", total));
    std::vector<std::size_t> at(axes.size(), 0);
    for (int index = 0; index < static_cast<int>(total); ++index) {
      Point p;
      p.index = index;
      for (std::size_t k = 0; k < axes.size(); ++k) p.values.push_back(axes[k][at[k]]);
      points.push_back(std::move(p));
      for (std::size_t k = axes.size(); k-- > 0;) {  // the last key changes fastest
        if (++at[k] < axes[k].size()) break;
        at[k] = 0;
      }
    }
    return points;
  }
  if (o.samples <= 0) throw DesignError(std::string("--method ") + to_string(o.method) + " needs --samples N (N > 0)");
  if (o.samples > 10'000'000) throw DesignError(tools::fmt("--samples %d (at most 10000000)", o.samples));
  const auto n = static_cast<std::size_t>(o.samples);
  Draws draws(o.seed);
  points.resize(n);
  for (std::size_t i = 0; i < n; ++i) points[i].index = static_cast<int>(i);
  for (const auto& s : specs) {
    if (o.method == Method::random) {
      for (auto& p : points) p.values.push_back(value_at(s, draws.uniform()));
      continue;
    }
    // Latin hypercube: stratum perm[i] of n for point i, a uniform position inside it.
    std::vector<std::size_t> perm(n);
    for (std::size_t i = 0; i < n; ++i) perm[i] = i;
    for (std::size_t i = n; i-- > 1;) std::swap(perm[i], perm[draws.below(i + 1)]);
    for (std::size_t i = 0; i < n; ++i)
      points[i].values.push_back(value_at(s, (static_cast<double>(perm[i]) + draws.uniform()) / static_cast<double>(n)));
  }
  return points;
}

}  // namespace mechsim::sweep

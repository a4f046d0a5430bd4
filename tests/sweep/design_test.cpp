// The design of a study (tools/sweep/design.h): the --vary grammar, the grid's size and
// order, exact values of linear and log ranges, and the Latin hypercube's stratification.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "design.h"

namespace mechsim::sweep {
namespace {

TEST(SweepDesign, ListKeepsEachEntryAsTheSceneGetsIt) {
  const VarySpec s = parse_vary("follower.spring.preload=100 N, 150 N");
  EXPECT_EQ(s.key, "follower.spring.preload");
  EXPECT_FALSE(s.is_range);
  EXPECT_EQ(s.list, (std::vector<std::string>{"100 N", "150 N"}));
  EXPECT_EQ(parse_vary("cam.law.0.type=half_cycloid_c1,full_cycloid").list.size(), 2u);
}

// (lo (n-1-i) + hi i)/(n-1): integers of the range come out exactly, and both ends are the typed ones.
TEST(SweepDesign, LinearRangeIsEvenAndExactAtTheEnds) {
  const VarySpec s = parse_vary("servo.position_gain=1..4:4");
  EXPECT_EQ(range_values(s), (std::vector<double>{1, 2, 3, 4}));
  const VarySpec t = parse_vary("x=0.1..0.3:3");
  const auto v = range_values(t);
  EXPECT_EQ(v.front(), 0.1);
  EXPECT_EQ(v.back(), 0.3);
  EXPECT_NEAR(v[1], 0.2, 1e-16);  // one rounding of (0.1 + 0.3) / 2
}

// Even in log10: pow(10, k) is exact for whole k, so a decade range gives its powers of ten.
TEST(SweepDesign, LogRangeGivesPowersOfTenExactly) {
  EXPECT_EQ(range_values(parse_vary("x=1..1000:4:log")), (std::vector<double>{1, 10, 100, 1000}));
  EXPECT_EQ(range_values(parse_vary("x=0.01..100:5:log")), (std::vector<double>{0.01, 0.1, 1, 10, 100}));
  // Between decades: the ratio of neighbours is constant (4^(1/2) = 2) to a rounding or two.
  const auto v = range_values(parse_vary("x=1..4:3:log"));
  EXPECT_NEAR(v[1], 2.0, 4e-16);
}

TEST(SweepDesign, RangeValuesCarryTheRangeUnit) {
  const VarySpec s = parse_vary("follower.spring.preload=10..40 N:4");  // the unit once
  EXPECT_EQ(s.unit, "N");
  const auto points = make_design({s}, {});
  ASSERT_EQ(points.size(), 4u);
  EXPECT_EQ(points[1].values[0].text, "20 N");
  EXPECT_EQ(points[1].values[0].number, 20);
  EXPECT_EQ(points[1].sets(), (std::vector<std::string>{"follower.spring.preload=20 N"}));
  // Two units of one dimension: the lower end in the upper one's unit.
  const VarySpec t = parse_vary("time.step=500 us..2 ms:4");
  EXPECT_EQ(t.unit, "ms");
  EXPECT_EQ(range_values(t), (std::vector<double>{0.5, 1, 1.5, 2}));
}

// Every combination, the last --vary changing fastest (as nested loops read).
TEST(SweepDesign, GridIsTheProductLastKeyFastest) {
  const auto points = make_design({parse_vary("a=1..3:3"), parse_vary("b=x,y,z,w")}, {});
  ASSERT_EQ(points.size(), 12u);
  EXPECT_EQ(points[0].sets(), (std::vector<std::string>{"a=1", "b=x"}));
  EXPECT_EQ(points[1].sets(), (std::vector<std::string>{"a=1", "b=y"}));
  EXPECT_EQ(points[4].sets(), (std::vector<std::string>{"a=2", "b=x"}));
  EXPECT_EQ(points[11].index, 11);
  EXPECT_TRUE(std::isnan(points[1].values[1].number));  // "y" has no number
}

TEST(SweepDesign, BadSpecsAreRefusedNamingTheKey) {
  const auto message = [](const std::string& spec) {
    try {
      parse_vary(spec);
    } catch (const DesignError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("servo.position_gain=1..4:1").find("empty range"), std::string::npos);
  EXPECT_NE(message("servo.position_gain=4..4:3").find("empty range"), std::string::npos);
  EXPECT_NE(message("servo.position_gain=0..4:3:log").find("log range"), std::string::npos);
  EXPECT_NE(message("servo.position_gain=").find("--vary servo.position_gain: no values"), std::string::npos);
  EXPECT_NE(message("servo.position_gain").find("expected KEY=SPEC"), std::string::npos);
  EXPECT_NE(message("x=1 s..4 N:3").find("not of one dimension"), std::string::npos);
  EXPECT_NE(message("x=1..4:three").find("whole count"), std::string::npos);
  EXPECT_NE(message("x=1..4:3:lin").find("'log'"), std::string::npos);
  EXPECT_NE(message("x=a,,b").find("empty entry"), std::string::npos);
  EXPECT_NE(message("x=1 furlong..4 furlong:3").find("unit"), std::string::npos);
  EXPECT_THROW(make_design({parse_vary("x=1..4")}, {}), DesignError);  // a grid needs a count
  EXPECT_THROW(make_design({parse_vary("x=1..4:4")}, {Method::grid, 10, 1}), DesignError);
  EXPECT_THROW(make_design({parse_vary("x=1..4")}, {Method::lhs, 0, 1}), DesignError);
  EXPECT_THROW(make_design({parse_vary("x=1,2"), parse_vary("x=3")}, {}), DesignError);
  EXPECT_THROW(parse_method("sobol"), DesignError);
}

// Each key's [lo, hi] cut into N equal strata (log: in log) holds exactly one of the N
// points; the same seed draws the same points, another seed others.
TEST(SweepDesign, LatinHypercubePutsOnePointInEachStratum) {
  const std::vector<VarySpec> specs{parse_vary("a=2..5"), parse_vary("b=1..1000:log"), parse_vary("c=p,q,r,s,t")};
  const int n = 25;
  const auto points = make_design(specs, {Method::lhs, n, 42});
  ASSERT_EQ(points.size(), static_cast<std::size_t>(n));
  std::set<int> strata_a, strata_b;
  std::map<std::string, int> entries;
  for (const auto& p : points) {
    const double a = p.values[0].number, b = p.values[1].number;
    ASSERT_GE(a, 2.0);
    ASSERT_LE(a, 5.0);
    strata_a.insert(static_cast<int>(std::floor((a - 2.0) / 3.0 * n)));
    strata_b.insert(static_cast<int>(std::floor(std::log10(b) / 3.0 * n)));
    ++entries[p.values[2].text];
  }
  EXPECT_EQ(strata_a.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(strata_b.size(), static_cast<std::size_t>(n));
  // 25 strata over 5 entries: each entry holds 5 of them.
  for (const auto& [entry, count] : entries) EXPECT_EQ(count, 5) << entry;
  const auto again = make_design(specs, {Method::lhs, n, 42});
  const auto other = make_design(specs, {Method::lhs, n, 43});
  int same = 0;
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(points[i].sets(), again[i].sets());
    same += points[i].values[0].text == other[i].values[0].text;
  }
  EXPECT_LT(same, 3);
}

TEST(SweepDesign, RandomDrawsStayInTheRangeAndRepeatWithTheSeed) {
  const std::vector<VarySpec> specs{parse_vary("a=-1..1")};
  const auto points = make_design(specs, {Method::random, 200, 7});
  double lo = 1, hi = -1;
  for (const auto& p : points) lo = std::min(lo, p.values[0].number), hi = std::max(hi, p.values[0].number);
  EXPECT_GE(lo, -1.0);
  EXPECT_LE(hi, 1.0);
  // 200 uniform draws leave a gap of more than 0.1 at an end with probability 2 (0.95)^200 < 1e-4.
  EXPECT_LT(lo, -0.9);
  EXPECT_GT(hi, 0.9);
  EXPECT_EQ(make_design(specs, {Method::random, 200, 7})[17].sets(), points[17].sets());
}

}  // namespace
}  // namespace mechsim::sweep

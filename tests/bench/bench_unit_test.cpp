// The pieces of `mechsim bench` that need no run: the order fit, the --steps grammar and
// the coupling-scheme variants it derives from a scene's connections.
#include <gtest/gtest.h>

#include <cmath>

#include "bench.h"

namespace mechsim::bench {
namespace {

TEST(BenchOrderFit, RecoversTheSlopeOfAPowerLaw) {
  // e = 3 h^2 exactly: the least-squares slope of log e against log h is 2 up to rounding
  // (1e-12 covers the log/exp round trip of doubles).
  std::vector<double> h{1e-4, 2e-4, 4e-4, 1e-3}, e;
  for (double x : h) e.push_back(3 * x * x);
  EXPECT_NEAR(fit_order(h, e), 2.0, 1e-12);
  // Non-finite or non-positive errors are skipped, not fitted.
  h.push_back(2e-3);
  e.push_back(NAN);
  h.push_back(4e-3);
  e.push_back(0.0);
  EXPECT_NEAR(fit_order(h, e), 2.0, 1e-12);
  // Fewer than three usable points: no order.
  EXPECT_TRUE(std::isnan(fit_order({1e-3, 2e-3}, {1.0, 2.0})));
}

TEST(BenchSteps, ParsesQuantitiesAndRefusesBadEntries) {
  const auto s = parse_steps("50 us, 25 us,1ms");
  ASSERT_EQ(s.size(), 3u);
  EXPECT_DOUBLE_EQ(s[0], 25e-6);  // sorted
  EXPECT_DOUBLE_EQ(s[1], 50e-6);
  EXPECT_DOUBLE_EQ(s[2], 1e-3);
  EXPECT_THROW(parse_steps("25 kg"), std::invalid_argument);
  EXPECT_THROW(parse_steps("fast"), std::invalid_argument);
  EXPECT_THROW(parse_steps("-1 ms"), std::invalid_argument);
  EXPECT_THROW(parse_steps(" , "), std::invalid_argument);
}

TEST(BenchTolerances, ParsesNumbersOrNone) {
  EXPECT_EQ(parse_tolerances("1e-3, 1e-2,1e-3"), (std::vector<double>{1e-2, 1e-3}));  // loosest first, once
  EXPECT_TRUE(parse_tolerances("none").empty());
  EXPECT_TRUE(parse_tolerances("").empty());
  EXPECT_THROW(parse_tolerances("1e-3,tight"), std::invalid_argument);
  EXPECT_THROW(parse_tolerances("0"), std::invalid_argument);
  EXPECT_THROW(parse_tolerances("2"), std::invalid_argument);
}

TEST(BenchEnvelope, LeastErrorAtNoMoreWallTimeInterpolatedLogLog) {
  // (wall, error): (1, 1e-2) and (4, 1e-4) are corners; (2, 5e-2) is above the envelope.
  const std::vector<std::pair<double, double>> p{{2, 5e-2}, {4, 1e-4}, {1, 1e-2}, {8, 1e-3}};
  int lo = -1, hi = -1;
  EXPECT_NEAR(envelope_at(p, 1, &lo, &hi), 1e-2, 1e-15);
  EXPECT_EQ(lo, 2);
  EXPECT_EQ(hi, 2);
  // Halfway in log wall time between the corners: halfway in log error.
  EXPECT_NEAR(envelope_at(p, 2, &lo, &hi), 1e-3, 1e-15);
  EXPECT_EQ(lo, 2);
  EXPECT_EQ(hi, 1);
  // After the last corner: flat.
  EXPECT_NEAR(envelope_at(p, 6, &lo, &hi), 1e-4, 1e-15);
  EXPECT_EQ(lo, 1);
  // Outside the wall time range of the points.
  EXPECT_TRUE(std::isnan(envelope_at(p, 0.5)));
  EXPECT_TRUE(std::isnan(envelope_at(p, 9)));
  EXPECT_TRUE(std::isnan(envelope_at({}, 1)));
}

// The cam press's connections: the cam's motion within the step, the follower's torque back
// one step late with the given reconstruction.
YAML::Node cam_press_connections(const std::string& reconstruction) {
  return YAML::Load("connections:\n  - {from: cam, to: follower, order: gauss_seidel}\n"
                    "  - {from: follower, to: cam, order: jacobi, reconstruction: " + reconstruction + "}\n");
}

TEST(BenchSchemes, ExplicitConnectionsGetJacobiAndGaussSeidelVariants) {
  const YAML::Node doc = cam_press_connections("hold");
  const auto v = scheme_variants(doc);
  std::vector<std::string> names;
  for (const auto& x : v) names.push_back(x.name);
  EXPECT_EQ(names, (std::vector<std::string>{"shipped", "jacobi/hold", "jacobi/linear", "jacobi/quadratic",
                                             "gauss_seidel/hold", "gauss_seidel/linear", "gauss_seidel/quadratic",
                                             "gauss_seidel_reversed/hold", "gauss_seidel_reversed/linear",
                                             "gauss_seidel_reversed/quadratic"}));
  EXPECT_TRUE(v[1].zero_order_hold_jacobi);
  EXPECT_EQ(v[1].document["connections"][0]["order"].as<std::string>(), "jacobi");
  EXPECT_EQ(v[2].document["connections"][1]["reconstruction"].as<std::string>(), "linear");
  EXPECT_EQ(v[5].document["connections"][0]["order"].as<std::string>(), "gauss_seidel");
  EXPECT_EQ(v[5].document["connections"][1]["reconstruction"].as<std::string>(), "linear");
  // The reversed ordering: the follower first, the cam's motion extrapolated.
  EXPECT_EQ(v[8].document["connections"][1]["order"].as<std::string>(), "gauss_seidel");
  EXPECT_EQ(v[8].document["connections"][0]["order"].as<std::string>(), "jacobi");
  EXPECT_EQ(v[8].document["connections"][0]["reconstruction"].as<std::string>(), "linear");
  // The input document is not changed.
  EXPECT_FALSE(doc["connections"][0]["reconstruction"]);
  // The shipped orders with the Jacobi edge quadratic are gauss_seidel/quadratic: that one is
  // marked for the adaptive points, no twin is added.
  for (std::size_t i = 0; i < v.size(); ++i) EXPECT_EQ(v[i].shipped_quadratic, i == 6) << v[i].name;
}

TEST(BenchSchemes, ACutGetsCompliantAndInterfaceJacobianVariants) {
  const YAML::Node doc = YAML::Load(R"(
connections:
  - {from: servo, to: tacho, order: jacobi, reconstruction: hold}
  - {from: tacho, to: slide, coupling: {scheme: interface_jacobian, levels: 10, stiffness: 23e3 N m/rad, damping: 0.15 N m s/rad}}
)");
  const auto v = scheme_variants(doc);
  ASSERT_EQ(v.size(), 8u);
  EXPECT_EQ(v[1].name, "compliant/hold");
  EXPECT_TRUE(v[1].zero_order_hold_jacobi);
  // Compliant: both directions of the cut, the element on one, no `levels`.
  const YAML::Node c = v[1].document["connections"];
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[1]["coupling"]["scheme"].as<std::string>(), "compliant");
  EXPECT_FALSE(c[1]["coupling"]["levels"]);
  EXPECT_EQ(c[1]["coupling"]["stiffness"].as<std::string>(), "23e3 N m/rad");
  EXPECT_EQ(c[2]["from"].as<std::string>(), "slide");
  EXPECT_EQ(c[2]["reconstruction"].as<std::string>(), "hold");
  // Interface Jacobian: one entry for the cut, the reverse dropped.
  EXPECT_EQ(v[4].name, "interface_jacobian/1");
  EXPECT_EQ(v[4].document["connections"].size(), 2u);
  EXPECT_EQ(v[4].document["connections"][1]["coupling"]["levels"].as<int>(), 1);
  // The shipped orders with every Jacobi edge quadratic, the interface Jacobian cut as it is
  // (no variant above has these connections, so it is added).
  EXPECT_EQ(v[7].name, "shipped/quadratic");
  EXPECT_TRUE(v[7].shipped_quadratic);
  EXPECT_EQ(v[7].document["connections"][0]["reconstruction"].as<std::string>(), "quadratic");
  EXPECT_FALSE(v[7].document["connections"][1]["reconstruction"]);
  EXPECT_EQ(v[7].document["connections"][1]["coupling"]["scheme"].as<std::string>(), "interface_jacobian");
  for (std::size_t i = 0; i < 7; ++i) EXPECT_FALSE(v[i].shipped_quadratic) << v[i].name;
}

TEST(BenchSchemes, NoQuadraticVariantWhereEveryJacobiEdgeIsQuadraticAlready) {
  for (const auto& x : scheme_variants(cam_press_connections("quadratic"))) {
    EXPECT_NE(x.name, "shipped/quadratic");
    EXPECT_FALSE(x.shipped_quadratic) << x.name;
  }
}

}  // namespace
}  // namespace mechsim::bench

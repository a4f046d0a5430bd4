// Model Exchange FMUs as blocks, integrated by mechsim's own SUNDIALS integrator
// (solve::BlockIntegrator, CVODE BDF) against their closed forms.
#include <cmath>

#include <gtest/gtest.h>

#include "fmu_files.h"
#include "mechsim/fmi/model_exchange_block.h"
#include "mechsim/solve/block_integrator.h"

namespace mechsim::fmi {
namespace {

using test::test_fmu;

solve::SolverOptions tight() {
  solve::SolverOptions o;
  o.method = solve::Method::cvode_bdf;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  return o;
}

class LagBlock : public ::testing::TestWithParam<const char*> {};

// The lag T dy/dt = k u - y (k = 2, T = 0.05 s, y0 = 0.5 V, u = 1 V): y = k u + (y0 - k u) e^(-t/T).
// CVODE at rtol 1e-10 / atol 1e-12 keeps each step's local error below ~1e-10 |y|; over the
// few hundred steps to 0.5 s on this contracting system the global error stays within a
// small multiple of that: 1e-8 V is asked, while a wrong parameter or port misses by > 1e-2 V.
TEST_P(LagBlock, CvodeMatchesTheClosedForm) {
  const auto archive = std::make_shared<const FmuArchive>(FmuLabel{test_fmu(GetParam()), "lag"});
  ModelExchangeBlock block(archive, {{"k", 2.0}, {"T", 0.05}, {"y0", 0.5}}, 0.0, 1.0);
  ASSERT_EQ(block.num_inputs(), 1);
  ASSERT_EQ(block.num_outputs(), 1);
  ASSERT_EQ(block.num_states(), 1);
  EXPECT_EQ(block.inputs()[0].name, "u");
  EXPECT_EQ(block.inputs()[0].unit, "V");
  EXPECT_EQ(block.outputs()[0].name, "y");
  EXPECT_TRUE(block.outputs()[0].feedthrough.empty());  // y is the state (<ModelStructure> dependencies)
  EXPECT_EQ(block.state_names(), std::vector<std::string>{"y"});
  double x0 = 0.0;
  block.initial_state(0.0, {&x0, 1});
  EXPECT_EQ(x0, 0.5);
  solve::BlockIntegrator integrator(block, tight(), 0.0, {&x0, 1});
  const auto input = [](double, std::span<double> u) { u[0] = 1.0; };
  double worst = 0.0;
  for (int n = 1; n <= 50; ++n) {
    const double t = n * 0.01;
    integrator.advance_to(t, input);
    double y = 0.0;
    const double u[] = {1.0};
    block.calc_outputs(t, integrator.state(), u, {&y, 1});
    worst = std::max(worst, std::abs(y - (2.0 - 1.5 * std::exp(-t / 0.05))));
  }
  EXPECT_LT(worst, 1e-8);
}

INSTANTIATE_TEST_SUITE_P(TestFmus, LagBlock, ::testing::Values("lag_fmi2_me", "lag_fmi3_me"));

class BouncingBlock : public ::testing::TestWithParam<const char*> {};

// The bouncing mass's impacts found by CVODE's root finding on the FMU's event indicator,
// the jump done by the FMU's event iteration: with a fixed floor (lift = 0), h0 = 1 m,
// e = 0.8, the impacts are at t1 = sqrt(2 h0/g) = 0.45152 s and t1 (1 + 2 e) = 1.17396 s,
// the apex between them at e² h0 = 0.64 m. The root is located to ~1e-10 s, the flight
// integrated to rtol 1e-10: 1e-7 m on the height and 1e-6 s on the impact times are asked;
// a missed impact, a doubled one or a wrong restitution misses by centimetres.
TEST_P(BouncingBlock, ImpactsFoundByTheIntegrator) {
  const auto archive = std::make_shared<const FmuArchive>(FmuLabel{test_fmu(GetParam()), "mass"});
  ModelExchangeBlock block(archive, {{"restitution", 0.8}}, 0.0, 2.0);
  ASSERT_EQ(block.num_event_functions(), 2);  // its event indicator, then the time-event function
  EXPECT_EQ(block.state_names(), (std::vector<std::string>{"height", "velocity"}));
  std::vector<double> x(2);
  block.initial_state(0.0, x);
  solve::BlockIntegrator integrator(block, tight(), 0.0, x);
  const double g = 9.81, t1 = std::sqrt(2.0 / g), apex_time = t1 + 0.8 * t1;
  integrator.advance_to(apex_time, {});
  std::vector<double> y(static_cast<std::size_t>(block.num_outputs()));
  block.calc_outputs(apex_time, integrator.state(), {}, y);
  EXPECT_NEAR(y[block.output_index("height")], 0.64, 1e-7);
  EXPECT_NEAR(y[block.output_index("velocity")], 0.0, 1e-6);
  EXPECT_EQ(y[block.output_index("impacts")], 1.0);
  integrator.advance_to(1.6, {});
  block.calc_outputs(1.6, integrator.state(), {}, y);
  EXPECT_EQ(y[block.output_index("impacts")], 2.0);
  const double t2 = t1 * 2.6, v2 = 0.64 * g * t1;
  EXPECT_NEAR(y[block.output_index("height")], v2 * (1.6 - t2) - 0.5 * g * (1.6 - t2) * (1.6 - t2), 1e-7);
  std::vector<double> falling_impacts;
  for (const auto& e : integrator.take_events())
    if (e.direction < 0) falling_impacts.push_back(e.t);
  ASSERT_EQ(falling_impacts.size(), 2u);
  EXPECT_NEAR(falling_impacts[0], t1, 1e-6);
  EXPECT_NEAR(falling_impacts[1], t2, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(TestFmus, BouncingBlock, ::testing::Values("bouncing_mass_fmi2_me", "bouncing_mass_fmi3_me"));

TEST(ModelExchangeBlock, SceneParametersTheFmuLacksAreRefused) {
  const std::string file = test_fmu("lag_fmi3_me");
  const auto archive = std::make_shared<const FmuArchive>(FmuLabel{file, "lag"});
  try {
    ModelExchangeBlock block(archive, {{"k_p", 40.0}}, 0.0, 1.0);
    ADD_FAILURE() << "not refused";
  } catch (const FmuError& e) {
    EXPECT_NE(std::string(e.what()).find("FMU '" + file + "' (participant 'lag'): has no variable 'k_p'"),
              std::string::npos)
        << e.what();
  }
  try {
    ModelExchangeBlock block(archive, {{"y", 1.0}}, 0.0, 1.0);
    ADD_FAILURE() << "not refused";
  } catch (const FmuError& e) {
    EXPECT_NE(std::string(e.what()).find("variable 'y' has causality output and type Float64; the scene sets parameters"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mechsim::fmi

// The interface-Jacobian coupling's pieces (libs/cosim/coupling): the torque solve, the
// prediction with its sensitivity, the message round trip, and the scene rules of the cut.
#include <gtest/gtest.h>

#include <cmath>

#include "mechsim/config/config_node.h"
#include "mechsim/cosim/composer.h"
#include "mechsim/cosim/coupling/interface_jacobian.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/models/nc/slide_block.h"
#include "mechsim/solve/block_integrator.h"
#include "scene_files.h"

namespace mechsim::cosim {
namespace {

using coupling::InterfacePrediction;

InterfacePrediction prediction(double angle, std::vector<double> predicted, std::vector<double> s) {
  return {angle, 0.5, std::move(predicted), std::move(s)};
}

TEST(InterfaceJacobian, SolvedLevelsObeyTheTrapezoidalLawOnTheCorrectedTwist) {
  const coupling::SpringDamper law{23e3, 0.15};
  const double h_macro = 1e-3;
  const auto plus = prediction(0.010, {0.0102, 0.0105, 0.0109}, {-2e-6, -7e-6, -1.5e-5});
  const auto minus = prediction(0.0099, {0.0100, 0.0101, 0.0103}, {1e-6, 3e-6, 6e-6});
  const std::vector<double> t = coupling::solve_torque_levels(law, h_macro, plus, minus);
  ASSERT_EQ(t.size(), 3u);
  const double h = h_macro / 3;
  // The twist each side will reach with these levels (linear model: prediction plus the
  // shifted sensitivities times the corrections), then the law level by level.
  double q_previous = plus.angle - minus.angle;
  for (int j = 0; j < 3; ++j) {
    double q = plus.predicted[j] - minus.predicted[j];
    for (int i = 0; i <= j; ++i)
      q += (plus.sensitivity[j - i] - minus.sensitivity[j - i]) * (t[i] - plus.assumed_torque);
    const double expected = law.stiffness * (q + q_previous) / 2 + law.damping * (q - q_previous) / h;
    // Forward substitution of a 3x3 triangular system: rounding only.
    EXPECT_NEAR(t[j], expected, 1e-12 * std::abs(expected)) << "level " << j;
    q_previous = q;
  }
}

TEST(InterfaceJacobian, BothSidesMustAgreeOnLevelsAndAssumedTorque) {
  const coupling::SpringDamper law{1e3, 0.0};
  auto plus = prediction(0, {0, 0}, {-1e-3, -2e-3});
  auto minus = prediction(0, {0, 0}, {1e-3, 2e-3});
  minus.assumed_torque = 0.6;
  EXPECT_THROW(coupling::solve_torque_levels(law, 1e-3, plus, minus), std::invalid_argument);
  minus = prediction(0, {0}, {1e-3});
  EXPECT_THROW(coupling::solve_torque_levels(law, 1e-3, plus, minus), std::invalid_argument);
  // Swapped sides (the torque would push the twist further): refused, not solved.
  EXPECT_THROW(coupling::solve_torque_levels(law, 1e-3, prediction(0, {0, 0}, {1, 2}), prediction(0, {0, 0}, {-1, -2})),
               std::invalid_argument);
}

TEST(InterfaceJacobian, MessageRoundTripKeepsEveryBit) {
  const auto p = prediction(0.1234567890123, {1.0 / 3, 2.0 / 7}, {-1e-7 / 3, -2e-7 / 3});
  std::vector<double> fields;
  coupling::to_fields(p, fields);
  ASSERT_EQ(fields.size(), 3u + 2 * coupling::kMaxLevels);
  EXPECT_TRUE(std::isnan(fields.back()));  // unused levels
  const auto q = coupling::from_fields(fields);
  EXPECT_EQ(q.angle, p.angle);
  EXPECT_EQ(q.assumed_torque, p.assumed_torque);
  EXPECT_EQ(q.predicted, p.predicted);
  EXPECT_EQ(q.sensitivity, p.sensitivity);
}

TEST(InterfaceJacobian, PredictionPlusSensitivityIsTheResponseOfALinearBlock) {
  // The NC slide (two-mass, viscous guide friction: linear) in torque mode, from a moving
  // state: predict 10 levels with an assumed torque, then integrate with other levels. For a
  // linear block prediction + shifted sensitivity x correction is the response exactly; the
  // difference is the integrator's error (rtol 1e-10 here).
  models::nc::SlideBlock slide;
  const int torque = slide.input_index("drive_torque"), angle = slide.output_index("spindle_angle");
  ASSERT_GE(torque, 0);
  std::vector<double> x0{0.02, 0.019, 3.0, 2.5};
  solve::SolverOptions options;
  options.rtol = 1e-10;
  options.atol = 1e-13;
  solve::BlockIntegrator integrator(slide, options, 0.0, x0);
  coupling::InterfaceSide side(slide, torque, angle, 10);
  const solve::InputFunction no_inputs = [](double, std::span<double>) {};
  const InterfacePrediction p = side.predict(integrator, 1e-3, no_inputs, 1.5);
  EXPECT_EQ(integrator.time(), 0.0);  // the prediction leaves the integrator where it was
  EXPECT_EQ(p.angle, 0.02);
  std::vector<double> levels(10);
  for (int j = 0; j < 10; ++j) levels[j] = 1.5 + 2.0 * std::sin(j);
  std::vector<double> actual;
  // Integrate level by level to read the angle at each sub-instant.
  for (int j = 0; j < 10; ++j) {
    integrator.mark_discontinuity();
    integrator.advance_to((j + 1) * 1e-4, [&](double, std::span<double> u) { u[torque] = levels[j]; });
    actual.push_back(integrator.state()[0]);
  }
  double largest_correction = 0;
  for (int j = 0; j < 10; ++j) {
    double predicted = p.predicted[j];
    for (int i = 0; i <= j; ++i) predicted += p.sensitivity[j - i] * (levels[i] - 1.5);
    largest_correction = std::max(largest_correction, std::abs(predicted - p.predicted[j]));
    // 1e-9 rad: the integrator's tolerance on angles of 0.02-0.05 rad, far below the
    // corrections (about 1e-6 rad) the sensitivities add.
    EXPECT_NEAR(actual[j], predicted, 1e-9) << "sub-instant " << j + 1;
  }
  EXPECT_GT(largest_correction, 1e-7);
}

std::string nc_1ms_with(const std::string& from, const std::string& to) {
  std::string text = testing::read_file(testing::shipped_scene("nc_slide_loop_1ms.yaml"));
  auto pos = text.find(from);
  if (pos == std::string::npos) throw std::runtime_error("no '" + from + "'");
  return text.replace(pos, from.size(), to);
}

TEST(InterfaceJacobian, SceneRulesOfTheCut) {
  const std::string cut = "  - {from: tacho, to: slide,\n";
  auto refused = [](const std::string& text) -> std::string {
    try {
      auto scene = std::make_unique<config::Scene>(config::load_scene(testing::write_scene(text)));
      ScenePlan::build(*scene);
    } catch (const config::ConfigError& e) {
      return e.what();
    }
    return "";
  };
  // The shipped scene plans: both sides have the cut, with the declared levels.
  auto scene = std::make_unique<config::Scene>(config::load_scene(testing::shipped_scene("nc_slide_loop_1ms.yaml")));
  ScenePlan plan = ScenePlan::build(*scene);
  ASSERT_TRUE(plan.node("tacho").cut && plan.node("slide").cut);
  EXPECT_EQ(plan.node("tacho").cut->levels, 10);
  EXPECT_EQ(plan.node("tacho").cut->twist_sign, -plan.node("slide").cut->twist_sign);
  EXPECT_EQ(plan.node("slide").cut->partner_topic, "tacho/coupling");
  // A second connection across the same cut.
  EXPECT_NE(refused(nc_1ms_with(cut, "  - {from: slide, to: tacho}\n" + cut)).find("joins them both ways"), std::string::npos);
  // Gauss-Seidel order on the cut.
  EXPECT_NE(refused(nc_1ms_with(cut, "  - {from: tacho, to: slide, order: gauss_seidel,\n")).find("order: jacobi"),
            std::string::npos);
  // Levels out of range, or given to another scheme.
  EXPECT_NE(refused(nc_1ms_with("levels: 10", "levels: 17")).find("1..16"), std::string::npos);
  EXPECT_NE(refused(nc_1ms_with("scheme: interface_jacobian, levels: 10", "scheme: compliant, levels: 10")).find("only with"),
            std::string::npos);
  // Quadratic reconstruction is a known key value.
  EXPECT_EQ(refused(nc_1ms_with("reconstruction: hold}", "reconstruction: quadratic}")), "");
}

TEST(InterfaceJacobian, TheReferenceJoinsTheCutOnce) {
  // The composed reference evaluates the coupling element once from both sides' angle and
  // speed: the slide's published coupling torque equals C (phi1 - phi_a) + d (w1 - w_a).
  auto scene = std::make_unique<config::Scene>(
      config::load_scene(testing::shipped_scene("nc_slide_loop_1ms.yaml"), {"time.end=20ms"}));
  ScenePlan plan = ScenePlan::build(*scene);
  ReferenceRun ref = run_reference(plan);
  const auto& torque = ref.log.data[ref.log.column("slide.coupling_torque")];
  const auto& phi1 = ref.log.data[ref.log.column("tacho.motor_angle")];
  const auto& w1 = ref.log.data[ref.log.column("tacho.motor_speed")];
  const auto& phia = ref.log.data[ref.log.column("slide.spindle_angle")];
  const auto& wa = ref.log.data[ref.log.column("slide.spindle_speed")];
  double largest = 0;
  for (std::size_t k = 0; k < torque.size(); ++k) {
    EXPECT_NEAR(torque[k], 23e3 * (phi1[k] - phia[k]) + 0.15 * (w1[k] - wa[k]), 1e-9 * (1 + std::abs(torque[k])));
    largest = std::max(largest, std::abs(torque[k]));
  }
  EXPECT_GT(largest, 0.1);  // the step does load the coupling (N m)
}

}  // namespace
}  // namespace mechsim::cosim

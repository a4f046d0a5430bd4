// The monolithic composer wires the same blocks into one ODE; checked against the
// closed-form kinetostatics of the cam press (constant speed: theta = omega t), written here
// from spec/cam.md §1-3 with the scene's numbers, independently of the model code.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mechsim/cosim/composer.h"
#include "scene_files.h"

namespace mechsim::cosim {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180;

// spec/cam.md §1, the press cam of config/scenes/cam_press.yaml: S, S' = dS/dtheta and
// S'' over the cam angle (rad). C1 26.25-45 deg +5 mm, C2 45-120 deg +20 mm, full cycloid
// 140-210 deg -25 mm, dwells elsewhere.
struct Lift {
  double s, s1, s2;
};
Lift press_lift(double theta) {
  theta = std::fmod(theta, 2 * kPi);
  struct Segment {
    double start_deg, span_deg, lift;
    int kind;  // 1: first half of a cycloid, 2: second half, 3: full cycloid
  };
  const Segment law[] = {{26.25, 18.75, 5e-3, 1}, {45, 75, 20e-3, 2}, {140, 70, -25e-3, 3}};
  double before = 0;  // lift of the segments already completed
  for (const Segment& g : law) {
    const double a = g.start_deg * kDeg, beta = g.span_deg * kDeg, L = g.lift;
    if (theta < a) return {before, 0, 0};  // the dwell before the segment
    if (theta < a + beta) {
      const double x = (theta - a) / beta;
      switch (g.kind) {
        case 1:  // x - sin(pi x)/pi
          return {before + L * (x - std::sin(kPi * x) / kPi), L / beta * (1 - std::cos(kPi * x)),
                  L / (beta * beta) * kPi * std::sin(kPi * x)};
        case 2:  // x + sin(pi x)/pi
          return {before + L * (x + std::sin(kPi * x) / kPi), L / beta * (1 + std::cos(kPi * x)),
                  -L / (beta * beta) * kPi * std::sin(kPi * x)};
        default:  // x - sin(2 pi x)/(2 pi)
          return {before + L * (x - std::sin(2 * kPi * x) / (2 * kPi)), L / beta * (1 - std::cos(2 * kPi * x)),
                  L / (beta * beta) * 2 * kPi * std::sin(2 * kPi * x)};
      }
    }
    before += L;
  }
  return {before, 0, 0};
}

// spec/cam.md §3: the functional loads on half-open intervals [a, b), + when the cam pushes.
double press_load(double theta) {
  const double deg = std::fmod(theta, 2 * kPi) / kDeg;
  if (deg >= 45 && deg < 100) return 100;
  if (deg >= 100 && deg < 120) return -230;
  if (deg >= 180 && deg < 210) return -120;
  return 0;
}

TEST(Composer, ReferenceOfTheCamPressMatchesTheClosedFormKinetostatics) {
  config::Scene scene = config::load_scene(testing::shipped_scene("cam_press.yaml"));
  ScenePlan plan = ScenePlan::build(scene);
  ReferenceRun ref = run_reference(plan);
  // The scene's numbers: 30 rpm, R0 = 65 mm, e = 0, m = 25 kg, k = 9 N/mm, F0 = 125 N.
  const double omega = kPi, r0 = 65e-3, m = 25, k = 9e3, f0 = 125;
  const auto& t = ref.log.data[0];
  const auto& n = ref.log.data[ref.log.column("follower.contact_force")];
  const auto& alpha_log = ref.log.data[ref.log.column("cam.pressure_angle")];
  const auto& m_shaft = ref.log.data[ref.log.column("cam.shaft_torque")];
  const auto& m_drive = ref.log.data[ref.log.column("follower.drive_torque")];
  ASSERT_EQ(t.size(), 2004u);  // 2000 steps of 1 ms, 3 landed on load boundaries off the grid
  double worst_n = 0, worst_alpha = 0, worst_torque = 0, largest_n = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double theta = omega * t[i];
    const Lift p = press_lift(theta);
    // §2: tan(alpha) = (S' - e)/(sqrt(R0^2 - e^2) + S), e = 0.
    const double alpha = std::atan(p.s1 / (r0 + p.s));
    // §3: N cos(alpha) = F_func + F0 + k S + m omega^2 S''. A row landed on a load boundary
    // (the composer's event) may hold either side's load: the nearer of the two.
    auto normal = [&](double load) { return (load + f0 + k * p.s + m * omega * omega * p.s2) / std::cos(alpha); };
    double error = std::abs(n[i] - normal(press_load(theta)));
    for (double edge : {45.0, 100.0, 120.0, 180.0, 210.0})
      if (std::abs(std::fmod(theta, 2 * kPi) - edge * kDeg) < 1e-9)
        error = std::min({error, std::abs(n[i] - normal(press_load(edge * kDeg - 1e-6))),
                          std::abs(n[i] - normal(press_load(edge * kDeg + 1e-6)))});
    worst_n = std::max(worst_n, error);
    largest_n = std::max(largest_n, std::abs(n[i]));
    worst_alpha = std::max(worst_alpha, std::abs(alpha_log[i] - alpha));
    // §4 without friction: the shaft power equals the follower power, M omega = N cos(alpha) S' omega.
    worst_torque = std::max(worst_torque, std::abs(m_drive[i] - n[i] * std::cos(alpha) * p.s1));
    // The composer evaluates the feedthrough chain follower -> cam in one pass: no lag.
    ASSERT_EQ(m_shaft[i], m_drive[i]) << "step " << i;
  }
  // The same formulas evaluated in another order: rounding only, far below 1e-9 of forces
  // of ~1e3 N (1e-9 rad, 1e-9 of torques of ~50 N m); a wrong wire, a load on the wrong
  // interval or a sign would be off by newtons.
  EXPECT_GT(largest_n, 400.0);  // the comparison covers the loaded strokes (N up to 438 N)
  EXPECT_LT(worst_n, 1e-9 * 1e3);
  EXPECT_LT(worst_alpha, 1e-9);
  EXPECT_LT(worst_torque, 1e-9 * 50);
}

}  // namespace
}  // namespace mechsim::cosim

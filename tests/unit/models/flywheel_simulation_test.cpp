// The dynamic cam shaft in time (spec cam.md §4): the design flywheel under the design's
// constant mean torque, and a start-up on a motor line. Both run the shipped scene
// config/scenes/cam_press_flywheel.yaml through the monolithic composer (the reference of
// `mechsim launch`), so the scene, the node types and the blocks are checked together.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include <unistd.h>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/composer.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/models/cam/cam_shaft_block.h"
#include "mechsim/models/cam/force_analysis.h"
#include "mechsim/models/cam/geometry.h"
#include "mechsim/models/cam/press_cam.h"

namespace mechsim {
namespace {

constexpr double pi = std::numbers::pi;
const std::string kFlywheelScene = std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/cam_press_flywheel.yaml";

struct Trace {
  std::vector<double> t, angle, speed;
};

Trace reference_trace(const config::Scene& scene, const models::cam::CamShaftBlock** shaft = nullptr) {
  static std::vector<std::unique_ptr<cosim::ScenePlan>> keep;  // the block outlives the call
  keep.push_back(std::make_unique<cosim::ScenePlan>(cosim::ScenePlan::build(scene)));
  cosim::ScenePlan& plan = *keep.back();
  if (shaft) *shaft = dynamic_cast<const models::cam::CamShaftBlock*>(plan.node("cam").block.get());
  const cosim::ReferenceRun ref = cosim::run_reference(plan);
  return {ref.log.data[0], ref.log.data[ref.log.column("cam.angle")], ref.log.data[ref.log.column("cam.speed")]};
}

// Time at which the (increasing) angle passes `angle`, linearly interpolated between samples.
double time_at_angle(const Trace& tr, double angle) {
  for (std::size_t k = 1; k < tr.t.size(); ++k)
    if (tr.angle[k] >= angle) {
      const double f = (angle - tr.angle[k - 1]) / (tr.angle[k] - tr.angle[k - 1]);
      return tr.t[k - 1] + f * (tr.t[k] - tr.t[k - 1]);
    }
  ADD_FAILURE() << "the shaft never reached " << angle << " rad";
  return NAN;
}

// The press cam's mean load torque and flywheel design at the nominal 30 rpm, K = 0.1.
models::cam::TorqueAnalysis press_torque() {
  const models::cam::PressCam c;
  return models::cam::drive_torque_analysis(c.law(), c.follower, c.speed_rad_s);
}

TEST(FlywheelSimulation, DesignFlywheelHoldsTheSpeedFluctuationNearK) {
  const config::Scene scene = config::load_scene(kFlywheelScene);
  const models::cam::CamShaftBlock* shaft = nullptr;
  const Trace tr = reference_trace(scene, &shaft);
  ASSERT_NE(shaft, nullptr);
  const auto torque = press_torque();
  const auto design = models::cam::flywheel_design(torque, 0.1, pi, 7800.0, 0.05);
  // The scene states the design to 5 digits (torque 0.45833 N m, disc radius 329.23 mm,
  // i.e. 4 × 1.5e-5 relative in I).
  ASSERT_NEAR(shaft->params().drive.torque_nm, torque.mean_torque_nm, 1e-5);
  ASSERT_NEAR(shaft->params().inertia_kgm2, design.inertia_kgm2, 1e-4 * design.inertia_kgm2);

  // The second revolution (the first starts at θ = 0 with the speed given, not with the
  // periodic one; with a constant torque equal to the mean there is no transient anyway).
  const double t_begin = time_at_angle(tr, 2 * pi), t_end = time_at_angle(tr, 4 * pi);
  const double mean = 2 * pi / (t_end - t_begin);
  double w_max = -1, w_min = 1e9, at_max = 0, at_min = 0;
  for (std::size_t k = 0; k < tr.t.size(); ++k) {
    if (tr.t[k] < t_begin || tr.t[k] > t_end) continue;
    if (tr.speed[k] > w_max) w_max = tr.speed[k], at_max = tr.angle[k];
    if (tr.speed[k] < w_min) w_min = tr.speed[k], at_min = tr.angle[k];
  }
  const double k_sim = (w_max - w_min) / mean;
  std::cout << "flywheel I = " << shaft->params().inertia_kgm2 << " kg m^2: w_max " << w_max << " at "
            << models::cam::rad_to_deg(at_max - 2 * pi) << " deg, w_min " << w_min << " at "
            << models::cam::rad_to_deg(at_min - 2 * pi) << " deg, mean " << mean << " rad/s, K_sim " << k_sim
            << " (design K 0.1 at " << pi << " rad/s)\n";
  // The brief's check: within 20 % of K. Started at ω_avg at θ = 0, close to the angle of
  // highest speed, the shaft runs ~5 % below ω_avg on average, and K ∝ 1/ω²: ≈ 0.11.
  EXPECT_NEAR(k_sim, 0.1, 0.02);
  // The design's energy balance itself, sharper: ½ I (ω_max² − ω_min²) = A_max. It ignores
  // only the follower's kinetic energy difference at the two angles from the design speed,
  // ½ m S'² (ω² − ω_avg²) ≤ 2e-4 J (m S'² ≤ 4.4e-4 kg m² there), i.e. 3e-5 of A_max, and the
  // scene's rounding (1e-4): 1e-3 of A_max bounds both.
  const double swing = 0.5 * shaft->params().inertia_kgm2 * (w_max * w_max - w_min * w_min);
  EXPECT_NEAR(swing, torque.a_max_j, 1e-3 * torque.a_max_j);
  // Fastest at argmin A, slowest at argmax A (spec §4's note), to the sampling (1 ms at
  // ~3 rad/s: 0.18°) plus the shift by that kinetic-energy term: 0.5°.
  EXPECT_NEAR(models::cam::rad_to_deg(at_max - 2 * pi), models::cam::rad_to_deg(torque.theta_a_min_rad), 0.5);
  EXPECT_NEAR(models::cam::rad_to_deg(at_min - 2 * pi), models::cam::rad_to_deg(torque.theta_a_max_rad), 0.5);
}

TEST(FlywheelSimulation, MotorLineStartsUpFromRestToTheSteadyMeanSpeed) {
  // The flywheel scene driven by a motor line instead, starting from rest.
  std::ifstream in(kFlywheelScene);
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::string from = "drive: {type: constant_torque, torque: 0.45833 N m}";
  const auto pos = text.find(from);
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, from.size(), "drive: {type: motor_line, stall_torque: 20 N m, no_load_speed: 31 rpm}");
  const auto path = std::filesystem::temp_directory_path() / ("mechsim-motor-start-" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(path) << text;
  const config::Scene scene = config::load_scene(path.string(), {"participants.cam.params.initial_speed=0 rpm", "time.end=20 s"});
  std::filesystem::remove(path);
  const models::cam::CamShaftBlock* shaft = nullptr;
  const Trace tr = reference_trace(scene, &shaft);
  ASSERT_EQ(tr.speed.front(), 0.0);

  // Steady state: over a revolution the drive's work ∮T dθ = T_s (2π − ∮ω dθ/ω0) equals the
  // load's 2π M_mean (spring and inertia do no net work), so the angle-mean speed is
  // ω0 (1 − M_mean/T_s) exactly; the time mean 2π/T_rev is the harmonic mean over the angle,
  // below it by about the variance of ω/ω̄ (≈ 0.05²/2 ≈ 0.13 % for the ±5 % this flywheel
  // allows). The transient decays with τ = I ω0/T_s ≈ 1.2 s: after 20 s, e^(−17). So 0.5 %
  // is ample (the brief asks for 2 %).
  const double expected = models::cam::motor_line_steady_speed(shaft->params().drive, press_torque().mean_torque_nm);
  const double last_turn = std::floor(tr.angle.back() / (2 * pi)) * 2 * pi;
  const double mean = 2 * pi / (time_at_angle(tr, last_turn) - time_at_angle(tr, last_turn - 2 * pi));
  double t_98 = NAN;  // first revolution whose mean speed is within 2 % of the steady one
  for (double a = 2 * pi; a <= last_turn; a += 2 * pi)
    if (2 * pi / (time_at_angle(tr, a) - time_at_angle(tr, a - 2 * pi)) > 0.98 * expected) {
      t_98 = time_at_angle(tr, a);
      break;
    }
  const double tau = shaft->params().inertia_kgm2 * shaft->params().drive.no_load_speed_rad_s /
                     shaft->params().drive.stall_torque_nm;
  std::cout << "motor line: steady mean speed " << mean << " rad/s, expected " << expected << " (error "
            << (mean / expected - 1) * 100 << " %); revolution mean within 2 % after " << t_98
            << " s (time constant I w0/T_s = " << tau << " s)\n";
  EXPECT_NEAR(mean, expected, 0.005 * expected);
  EXPECT_LT(t_98, 20.0);
}

}  // namespace
}  // namespace mechsim

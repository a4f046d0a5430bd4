// The press line (config/scenes/press_line.yaml, docs/press-line.md) through `mechsim launch`:
// cvt -> gear -> cam_shaft -> follower as three processes over loopback DDS, compared with the
// monolithic reference built from the same blocks; the energy balance of the run summary.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "run_fixture.h"

namespace mechsim::testing {
namespace {

using nlohmann::json;

class PressLine : public RunFolderTest {};

TEST_F(PressLine, EnergyBalanceClosesAndTheRunMatchesTheReference) {
  CommandResult r = run(launch_args(scene_path("press_line.yaml"), "a"), log("a"), 120);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json s = summary("a");
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["steps"], 2000);
  // How long the launch takes is measured by tools/bench-lockstep.sh, not asserted here.

  // Energy: motor work = belt and bearing losses + press work + change of the kinetic
  // (CVT shafts, cam shaft and flywheel, follower) and spring energy.
  const json& e = figure(s, "energy_balance", "cvt.motor_power");
  const double supplied = e["supplied_J"].get<double>();
  EXPECT_GT(supplied, 1e4);  // ~13.4 kJ: three strokes of 2.87 kJ plus spinning up the flywheel
  // The reference integrates one ODE at rtol 1e-10 and the figure integrates the sampled
  // powers with the trapezoidal rule at H = 1 ms. The powers are continuous (the forming force
  // starts at 0 and ends where the ram stops), so the rule's error is H²/12·∫|P''| dt: with
  // P'' ~ P/τ² for the forming stroke's τ ≈ 0.1 s that is ~1e-4·P·T/12, and 1e-4 of the
  // supplied work bounds it (measured 1.5e-5).
  EXPECT_LT(e["reference"]["relative_residual"].get<double>(), 1e-4);
  // The co-simulation exchanges the motion one macro step late (Jacobi, linear extrapolation;
  // the torques and inertias within the step, Gauss-Seidel): the CVT and the cam see each
  // other's power at slightly different times, which is the residual. Second order in H:
  // measured 3.1e-4 at 1 ms (3.0e-4 with the other ordering; 1.4e-3 with a held exchange,
  // 7e-4 at 0.5 ms held, i.e. first order as it should be); 1e-3 is the bound for the
  // scene's scheme, a held (first-order) exchange would break it.
  EXPECT_LT(e["relative_residual"].get<double>(), 1e-3);
  // The work terms agree with the reference's to the same order (the ratio step and the
  // forming strokes happen at the same times in both).
  EXPECT_NEAR(supplied, e["reference"]["supplied_J"].get<double>(), 2e-3 * supplied);

  // Against the reference (errors relative to the reference's range over the run). Measured
  // with the follower first and the motion extrapolated linearly (the scene since issue 31;
  // the other ordering gave belt torque 3.5 % max, the ratio step's transient crossed a step
  // late): input speed 0.11 %, output speed and cam speed ~0.11 %, belt torque 0.16 % max and
  // 0.03 % rms. The bounds are about 3x the measured values: a lost, doubled or reordered
  // sample costs a whole step of the 60 N m torque swing and breaks them.
  const json& sig = s["signals"];
  EXPECT_LT(sig["cvt.input_speed"]["max_rel_error"].get<double>(), 3e-3);
  EXPECT_LT(sig["cam.speed"]["max_rel_error"].get<double>(), 1e-2);
  EXPECT_LT(sig["cvt.ratio_setting"]["max_rel_error"].get<double>(), 1e-3);
  EXPECT_LT(sig["cvt.belt_torque"]["rms_rel_error"].get<double>(), 5e-3);
  EXPECT_LT(sig["cvt.belt_torque"]["max_rel_error"].get<double>(), 5e-3);
  EXPECT_LT(sig["follower.position"]["max_rel_error"].get<double>(), 1e-2);

  // The scene is designed to stay inside the thesis's model: positive T_C of 20-120 N m and
  // 1000-5000 rpm input, no gross slip. Nothing flagged in either run.
  for (const char* flag : {"cvt.torque_reversal", "cvt.gross_slip", "cvt.outside_model"}) {
    const json& f = figure(s, "time_true", flag);
    EXPECT_EQ(f["value"].get<double>(), 0.0) << flag;
    EXPECT_EQ(f["reference"]["value"].get<double>(), 0.0) << flag;
  }
  EXPECT_GE(figure(s, "min", "cvt.belt_torque")["value"].get<double>(), 20.0);
  EXPECT_LE(figure(s, "max", "cvt.belt_torque")["value"].get<double>(), 120.0);
  EXPECT_GE(figure(s, "min", "cvt.input_speed")["value"].get<double>(), 1000 * 3.14159265358979 / 30);
  // The ratio actually moved: the actuator's step (30 -> 20 mm at 0.8 s, τ = 0.15 s) settled.
  const json& step = figure(s, "step_response", "cvt.ratio_setting");
  EXPECT_TRUE(step["settled"].get<bool>());
}

}  // namespace
}  // namespace mechsim::testing

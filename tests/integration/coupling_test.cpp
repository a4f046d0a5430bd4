// The NC loop split in its three processes with the interface-Jacobian scheme on the stiff
// motor-spindle cut (config/scenes/nc_slide_loop_1ms.yaml), over DDS through `mechsim
// launch`, against the monolithic reference with the amplifier sampled identically (issue 6
// targets): stable at H = 1 ms, and at 250 us rise time and final position within 1 % and
// the RMS position error below 1 % of the step; the bounds are the measured errors with a
// stated margin, tight enough that the scheme with fewer torque levels fails them.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "run_fixture.h"

namespace mechsim::testing {
namespace {

using nlohmann::json;

constexpr double kStep = 1e-4;  // m: the scene's 0.1 mm position step

class InterfaceJacobianLoop : public RunFolderTest {
 protected:
  json launch(const std::string& tag, std::vector<std::string> extra = {}) {
    CommandResult r = run(launch_args(scene_path("nc_slide_loop_1ms.yaml"), tag, std::move(extra)), log(tag), 180);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return r.exit_code == 0 ? summary(tag) : json{};
  }
  static const json& step_figure(const json& s) {
    for (const auto& f : s["report"])
      if (f["stat"] == "step_response" && f["signal"] == "slide.slide_position") return f;
    throw std::runtime_error("no step response figure");
  }
};

TEST_F(InterfaceJacobianLoop, StableAtOneMillisecond) {
  json s = launch("h1ms");
  ASSERT_FALSE(s.is_null());
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["steps"].get<long>(), 200);  // 0.2 s at 1 ms: the whole response and its settling
  const json& x = s["signals"]["slide.slide_position"];
  EXPECT_TRUE(x["finite"].get<bool>());
  // The same bounds as in process (nc_coupling_test.cpp, where they are argued): over DDS
  // the run gives the in-process figures (RMS 0.0023 % of the step, rise -0.019 %); 2x and
  // 3x that, below the 2-level (0.0080 %) and 1-level (0.018 % / +0.14 %) scheme's: a
  // lost `levels` fails here too.
  EXPECT_LT(x["rms_abs_error"].get<double>(), 5e-5 * kStep);
  EXPECT_LT(std::abs(step_figure(s)["relative_difference"]["rise_time_s"].get<double>()), 6e-4);
}

TEST_F(InterfaceJacobianLoop, AccurateAt250Microseconds) {
  json s = launch("h250us", {"--step", "250 us", "--set", "servo.sample_time=250us"});
  ASSERT_FALSE(s.is_null());
  const json& step = step_figure(s);
  // Issue 6 asks for rise time and final position within 1 % and an RMS position error
  // below 1 % of the step; measured at the nodes' tolerance floor (RMS 0.0004 %, rise
  // -0.0006 %): the bounds of nc_coupling_test.cpp, 5x that floor.
  EXPECT_LT(std::abs(step["relative_difference"]["rise_time_s"].get<double>()), 1e-4);
  EXPECT_LT(std::abs(step["final_value"].get<double>() - step["reference"]["final_value"].get<double>()), 5e-5 * kStep);
  EXPECT_LT(s["signals"]["slide.slide_position"]["rms_abs_error"].get<double>(), 2e-5 * kStep);
  // The reference itself: the spec's step response (rise 34.4 ms continuous; sampling at
  // 250 us shifts it by about 0.2 %, coupling-facts.md), within 3 % as nc_loop_test allows.
  EXPECT_NEAR(step["reference"]["rise_time_s"].get<double>(), 0.0344, 0.03 * 0.0344);
}

}  // namespace
}  // namespace mechsim::testing

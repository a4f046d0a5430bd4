// The NC loop split in its three processes with the interface-Jacobian scheme on the stiff
// motor-spindle cut (config/scenes/nc_slide_loop_1ms.yaml), over DDS through `mechsim
// launch`, against the monolithic reference with the amplifier sampled identically (issue 6
// targets): stable at H = 1 ms, and at 250 us rise time and final position within 1 % and
// the RMS position error below 1 % of the step.
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
  // Stable and close: the in-process study measured 0.002 % RMS at 1 ms; 1 % of the step
  // (the target's accuracy bound at 250 us) is a generous ceiling a diverging or
  // first-order run would exceed.
  EXPECT_LT(x["rms_abs_error"].get<double>(), 0.01 * kStep);
}

TEST_F(InterfaceJacobianLoop, AccurateAt250Microseconds) {
  json s = launch("h250us", {"--step", "250 us", "--set", "servo.sample_time=250us"});
  ASSERT_FALSE(s.is_null());
  const json& step = step_figure(s);
  // Issue 6: rise time and final position within 1 %, RMS position error below 1 % of the
  // step, against the reference sampled identically at 250 us.
  EXPECT_LT(step["relative_difference"]["rise_time_s"].get<double>(), 0.01);
  EXPECT_LT(std::abs(step["final_value"].get<double>() - step["reference"]["final_value"].get<double>()), 0.01 * kStep);
  EXPECT_LT(s["signals"]["slide.slide_position"]["rms_abs_error"].get<double>(), 0.01 * kStep);
  // The reference itself: the spec's step response (rise 34.4 ms continuous; sampling at
  // 250 us shifts it by about 0.2 %, coupling-facts.md), within 3 % as nc_loop_test allows.
  EXPECT_NEAR(step["reference"]["rise_time_s"].get<double>(), 0.0344, 0.03 * 0.0344);
}

}  // namespace
}  // namespace mechsim::testing

// The worked example of docs/new-participant.md: the participant type `linear_scale` in the
// NC loop (config/scenes/nc_slide_scale.yaml), launched as a new user would, with its error
// against the monolithic reference and its lag against the closed form of a first-order lag.
// The tolerances are argued in docs/new-participant.md, section 6.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "run_fixture.h"

namespace mechsim::testing {
namespace {

using nlohmann::json;

class NewParticipant : public RunFolderTest {};

TEST_F(NewParticipant, TheLinearScaleRunsInTheNcLoopAndMeasuresTheSlideWithItsLag) {
  const std::string scene = scene_path("nc_slide_scale.yaml");
  CommandResult grouped = run(launch_args(scene, "grouped"), log("grouped"), 180);
  ASSERT_EQ(grouped.exit_code, 0) << grouped.output;
  CommandResult apart = run(launch_args_a_process_each(scene, "apart"), log("apart"), 180);
  ASSERT_EQ(apart.exit_code, 0) << apart.output;
  const json s = summary("grouped");
  // Results do not depend on placement: the scale's own executable and the process group
  // compute the same bytes.
  expect_identical_node_outputs(run_folder("grouped"), run_folder("apart"), s, "a process group and a process each");
  // The scale only watches: the loop's three participants step as in nc_slide_loop.yaml.
  CommandResult loop = run(launch_args(scene_path("nc_slide_loop.yaml"), "loop"), log("loop"), 180);
  ASSERT_EQ(loop.exit_code, 0) << loop.output;
  expect_identical_node_outputs(run_folder("grouped"), run_folder("loop"), std::vector<std::string>{"servo", "tacho", "slide"},
                                "nc_slide_scale and nc_slide_loop");

  // Against the reference: a unit-gain first-order lag does not amplify its input's error,
  // and the Gauss-Seidel edge adds at most H max|v| = 0.1 % of the range.
  const json& slide = s["signals"]["slide.slide_position"];
  const json& scale = s["signals"]["scale.measured_position"];
  ASSERT_TRUE(scale.is_object()) << s["signals"].dump();
  EXPECT_LE(scale["max_rel_error"].get<double>(), slide["max_rel_error"].get<double>() + 1e-3) << scale.dump();

  // The lag behind the moving slide: tau max|v| within 10 % (the tau^2 a term is a few per cent).
  const double tau = 1e-3;
  const double top_speed = figure(s, "max_abs", "slide.slide_speed")["value"].get<double>();
  const double largest_lag = figure(s, "max_abs", "scale.measurement_error")["value"].get<double>();
  EXPECT_GT(top_speed, 1e-3);  // the slide does move (3.4 mm/s at its fastest)
  EXPECT_NEAR(largest_lag, tau * top_speed, 0.10 * tau * top_speed);
  // Settled at the end: below 0.1 % of the 0.1 mm step.
  EXPECT_LT(std::abs(figure(s, "final", "scale.measurement_error")["value"].get<double>()), 1e-3 * 1e-4);
  // And the step response it reports reaches the target like the slide's.
  const json& step = figure(s, "step_response", "scale.measured_position");
  EXPECT_TRUE(step["settled"].get<bool>()) << step.dump();
}

}  // namespace
}  // namespace mechsim::testing

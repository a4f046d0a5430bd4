// LinearScaleBlock, the worked example of docs/new-participant.md, against its closed form.
#include "mechsim/models/nc/linear_scale_block.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "fixed_step_rk4.h"

namespace mechsim::models::nc {
namespace {

TEST(LinearScaleBlockTest, PortsAndFeedthrough) {
  const LinearScaleBlock dut;
  ASSERT_EQ(dut.num_inputs(), 1);
  EXPECT_TRUE(dut.inputs()[dut.input_index("slide_position")].required);
  EXPECT_TRUE(dut.outputs()[dut.output_index("measured_position")].feedthrough.empty());
  EXPECT_EQ(dut.outputs()[dut.output_index("measurement_error")].feedthrough, std::vector<int>{dut.input_index("slide_position")});
  EXPECT_EQ(dut.num_states(), 1);
}

TEST(LinearScaleBlockTest, FollowsAStepOfTheSlideAsAFirstOrderLag) {
  LinearScaleParams p;
  p.time_constant = 0.2e-3;
  p.offset = 2e-6;
  p.initial_position = 1e-5;
  LinearScaleBlock dut(p);
  const double a = 1e-4;  // the slide stands at 0.1 mm from t = 0
  // RK4 at h = τ/200: the global error is of order (h/τ)^4 / 120 ≈ 5e-12 of the step, far
  // below the 1e-9 asserted.
  const double h = p.time_constant / 200;
  const auto tr = testing::integrate_rk4(dut, 5 * p.time_constant, h, {a});
  const int measured = dut.output_index("measured_position"), error = dut.output_index("measurement_error");
  for (std::size_t k = 0; k < tr.time.size(); k += 50) {
    const double t = tr.time[k];
    const double x_m = a + (p.initial_position - a) * std::exp(-t / p.time_constant);
    EXPECT_NEAR(tr.outputs[k][measured], x_m + p.offset, 1e-9 * a) << "t = " << t;
    EXPECT_NEAR(tr.outputs[k][error], x_m + p.offset - a, 1e-9 * a) << "t = " << t;
  }
}

TEST(LinearScaleBlockTest, RefusesANonPositiveTimeConstant) {
  LinearScaleParams p;
  p.time_constant = 0;
  EXPECT_THROW(LinearScaleBlock{p}, std::invalid_argument);
}

}  // namespace
}  // namespace mechsim::models::nc

// A direct measuring system on the slide (a linear glass scale with its signal
// electronics): the worked example of docs/new-participant.md. The CNC 200 measures the
// position indirectly, through the spindle angle; a scale on the slide sees the slide itself,
// after its electronics' first-order lag:
//
//   τ dx_m/dt = x − x_m,      measured_position = x_m + offset,
//   measurement_error = measured_position − x
//
// with x the slide position. From rest at x_m(0) = initial_position, a step of the slide to
// a gives x_m(t) = a + (x_m(0) − a) e^(−t/τ); a ramp x = v t from x_m(0) = 0 gives
// x_m(t) = v (t − τ (1 − e^(−t/τ))), which lags the slide by v τ once settled.
//
// Ports                      unit   feedthrough
//   in  slide_position       m      required
//   out measured_position    m      none (from the state)
//   out measurement_error    m      slide_position
// State: measured (x_m) [m].
#pragma once

#include "mechsim/models/block.h"

namespace mechsim::models::nc {

struct LinearScaleParams {
  double time_constant = 0.2e-3;  // τ [s] of the signal electronics
  double offset = 0.0;            // mounting zero offset [m]
  double initial_position = 0.0;  // x_m(0) [m]
};

class LinearScaleBlock final : public Block {
 public:
  explicit LinearScaleBlock(LinearScaleParams params = {});

  void initial_state(double t0, std::span<double> x) const override;
  void derivatives(double t, std::span<const double> x, std::span<const double> u,
                   std::span<double> dxdt) const override;
  void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                    std::span<double> y) const override;

  const LinearScaleParams& params() const { return params_; }

 private:
  LinearScaleParams params_;
  int slide_position_, measured_position_, measurement_error_, measured_;
};

}  // namespace mechsim::models::nc

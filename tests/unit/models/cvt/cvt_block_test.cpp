// The CVT block with its drive (libs/models/include/mechsim/models/cvt/cvt_block.h): the
// power balance that its equations must close at any state (also while the ratio moves),
// the ratio actuator, a steady operating point against the stationary model, and the
// flagged state outside the model.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mechsim/models/cvt/cvt_block.h"

namespace cvt = mechsim::models::cvt;

namespace {

struct Eval {
  std::vector<double> dx, y;
};

Eval eval(const cvt::CvtBlock& b, std::vector<double> x, std::vector<double> u) {
  Eval e{std::vector<double>(b.num_states()), std::vector<double>(b.num_outputs())};
  b.derivatives(0.0, x, u, e.dx);
  b.calc_outputs(0.0, x, u, e.y);
  return e;
}

}  // namespace

// Motor power = load power + belt loss + bearing loss + d/dt of the kinetic energy
// (½J_C ω_C² + ½J_D ω_D², with ω̇_D = i ω̇_C + i'(s) ṡ ω_C). The block's T_C comes from a
// 4-pass fixed point, so the balance closes to the last pass's change of the losses: 1e-6 of
// the motor power is argued by the bearing/belt losses being ~10 % of T_C and changing by
// < 1e-5 between passes.
TEST(CvtBlock, PowerBalanceClosesWhileTheRatioMoves) {
  cvt::CvtBlockParams p;
  const cvt::CvtBlock b(p);
  for (double s_cmd : {30e-3, 45e-3, 10e-3}) {
    const std::vector<double> x{300.0, 30e-3}, u{s_cmd, 60.0, 0.0};
    const Eval e = eval(b, x, u);
    const cvt::CvtBlock::Solution sol = b.solve(x, u);
    const double w = x[0], i = sol.belt.ratio, wD = i * w;
    const double wD_dot = i * sol.omega_dot + sol.di_ds * sol.s_dot * w;
    const double P_motor = sol.T_M * w;
    const double P_load = u[1] * wD;
    const double P_loss = e.y[b.output_index("belt_loss")] + e.y[b.output_index("bearing_loss")];
    const double dE = p.J_C * w * sol.omega_dot + p.J_D * wD * wD_dot;
    EXPECT_NEAR(P_motor, P_load + P_loss + dE, 1e-6 * P_motor) << "s_cmd " << s_cmd;
    EXPECT_NEAR(e.dx[1], (s_cmd - x[1]) / p.ratio_time_constant, 1e-15);
  }
}

// At a steady point (ω̇ = 0, found by bisection on ω_C) the block's belt is the stationary
// model at T_C = T_1 − T_Lprim with the motor line giving T_1, and T_2 equals the load.
TEST(CvtBlock, SteadyStateIsTheStationaryModel) {
  cvt::CvtBlockParams p;
  const cvt::CvtBlock b(p);
  const double T_P = 80.0;
  double lo = 100.0, hi = 419.0;
  auto wdot = [&](double w) { return b.solve(std::vector<double>{w, 30e-3}, std::vector<double>{30e-3, T_P, 0.0}).omega_dot; };
  ASSERT_GT(wdot(lo), 0.0);
  ASSERT_LT(wdot(hi), 0.0);
  for (int k = 0; k < 60; ++k) {
    const double m = 0.5 * (lo + hi);
    (wdot(m) > 0 ? lo : hi) = m;
  }
  const std::vector<double> x{0.5 * (lo + hi), 30e-3}, u{30e-3, T_P, 0.0};
  const Eval e = eval(b, x, u);
  EXPECT_NEAR(e.y[b.output_index("output_torque")], T_P, 1e-3);  // the F_K steps make ω̇(ω) jump; 1e-3 Nm
  EXPECT_NEAR(e.y[b.output_index("input_torque")], e.y[b.output_index("motor_torque")], 1e-3);
  cvt::CvtModel m;
  cvt::CvtOperatingPoint op;
  op.s = 30e-3;
  op.omega_C = x[0];
  op.torque = e.y[b.output_index("belt_torque")];
  const cvt::CvtResult r = m.evaluate(op);
  // belt_torque is the equations' T_C after the last fixed-point pass, η_SYS the map at the
  // pass's T_C: they differ by the fixed-point residual (µN m here), which moves η_SYS by
  // dη_SYS/dT_C·ΔT ≈ 1e-4/N m · 1e-6 N m; 1e-9 leaves room for that and for nothing else.
  EXPECT_NEAR(e.y[b.output_index("eta_SYS")], r.eta_SYS, 1e-9);
  EXPECT_NEAR(e.y[b.output_index("clamping_force")], r.F_K, 1e-9);
}

// A load that drives the disc (torque reversal) is flagged, and the block still gives finite
// derivatives (lossless belt) instead of stopping the run.
TEST(CvtBlock, ReversalIsFlaggedNotFatal) {
  const cvt::CvtBlock b;
  const std::vector<double> x{300.0, 30e-3}, u{30e-3, -2000.0, 0.0};
  const Eval e = eval(b, x, u);
  EXPECT_TRUE(std::isfinite(e.dx[0]));
  const unsigned flags = static_cast<unsigned>(e.y[b.output_index("flags")]);
  EXPECT_NE(flags & cvt::kTorqueReversal, 0u) << cvt::flag_names(flags);
}

TEST(CvtBlock, RefusesBadParameters) {
  cvt::CvtBlockParams p;
  p.J_C = 0.0;
  EXPECT_THROW(cvt::CvtBlock{p}, cvt::CvtInputError);
  p = {};
  p.s0 = 80e-3;
  EXPECT_THROW(cvt::CvtBlock{p}, cvt::CvtInputError);
}

// The monolithic NC loop (spec nc_slide.md §3) and its step responses.
//
// Integration: fixed-step RK4 at h = 10 µs. The fastest closed-loop eigenvalues lie near
// 1e4 s⁻¹ (electrical pole, coupling mode, tacho filter), so h λ ≈ 0.1, well inside RK4's
// stability region; StepFiguresDoNotMoveWhenTheStepIsHalved shows the figures change by
// < 1e-5 relative at h/2, so the integration error is negligible against every tolerance.
#include "mechsim/models/nc/closed_loop_reference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "fixed_step_rk4.h"

namespace mechsim::models::nc {
namespace {

constexpr double step = 1e-5;

ClosedLoopOptions step_of(double distance) {
  ClosedLoopOptions o;
  o.amplifier.setpoint = {SetpointKind::step, 0.0, distance};
  return o;
}

struct StepRun {
  testing::StepMetrics metrics;
  double peak_current;
  double last_saturated_time;
};

StepRun run_step(ClosedLoopOptions options, double h = step, double t_end = 0.3) {
  ClosedLoopReference loop(options);
  const auto tr = testing::integrate_rk4(loop, t_end, h);
  const double target = options.amplifier.setpoint.distance;
  StepRun run{testing::step_metrics(tr.time, tr.signal(loop.output_index("slide_position")), target), 0, 0};
  const auto current = tr.signal(loop.output_index("armature_current"));
  const auto saturated = tr.signal(loop.output_index("saturated"));
  for (std::size_t i = 0; i < current.size(); ++i) {
    run.peak_current = std::max(run.peak_current, std::abs(current[i]));
    if (saturated[i] > 0.5) run.last_saturated_time = tr.time[i];
  }
  return run;
}

TEST(ClosedLoopReferenceTest, HasTheSpecsElevenStates) {
  const ClosedLoopReference loop;
  EXPECT_EQ(loop.num_states(), 11);
  EXPECT_EQ(loop.num_inputs(), 0);
  EXPECT_EQ(loop.state_names()[0], "servo_amplifier.integrator");
  EXPECT_EQ(loop.state_names()[10], "slide.slide_end_speed");
}

// The spec's equations written out once more, independently of the blocks.
std::vector<double> spec_derivatives(double phi_ref, const std::vector<double>& x) {
  const double alpha = 0.0496, kv = 40, ksv = 10, ti = 0.01, tau_f = 0.3e-3;
  const double ra = 0.27921, la = 6.62487e-5, c = 0.2, i1 = 1.2e-3, i2 = 1.79214e-4, k = 1272.23, b3 = 1e-2;
  const double ck = 23e3, dk = 0.15, dsp = 0.08;
  const double d = 0.035, l = 1.5, rho = 7850, g = 8e10, pi = std::numbers::pi;
  const double polar = pi * std::pow(d, 4) / 32, isp = rho * polar * l, csp = g * polar / l;
  const double r = 0.005 / (2 * pi);
  const double ia = 2.5e-4 + isp / 2, ib = 235 * r * r + isp / 2, guide = 2000 * r * r;
  const double z = x[0], utf = x[1], cur = x[2], w1 = x[3], w2 = x[4], th = x[5], p1 = x[6];
  const double pa = x[7], pb = x[8], wa = x[9], wb = x[10];
  const double e = alpha * kv * (phi_ref - pa) - utf;
  const double ua = ksv * e + z;  // unsaturated
  const double coupling = ck * (p1 - pa) + dk * (w1 - wa);
  const double spindle = csp * (pa - pb) + dsp * (wa - wb);
  return {ksv / ti * e,
          (alpha * w2 - utf) / tau_f,
          (ua - ra * cur - c * w1) / la,
          (c * cur - b3 * (w1 - w2) - k * th - coupling) / i1,
          (k * th + b3 * (w1 - w2)) / i2,
          w1 - w2,
          w1,
          wa,
          wb,
          (coupling - spindle) / ia,
          (spindle - guide * wb) / ib};
}

TEST(ClosedLoopReferenceTest, DerivativesMatchTheSpecEquations) {
  const ClosedLoopReference loop(step_of(1e-4));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    // Small states keep the amplifier inside ±50 V (checked), where the loop is linear.
    std::vector<double> x{0.5 * uniform(rng), 0.2 * uniform(rng), 2 * uniform(rng),  5 * uniform(rng),
                          5 * uniform(rng),   1e-4 * uniform(rng), 0.1 + 1e-3 * uniform(rng),
                          0.1 + 1e-3 * uniform(rng), 0.1 + 1e-3 * uniform(rng), 5 * uniform(rng), 5 * uniform(rng)};
    std::vector<double> dx(11), y(loop.num_outputs());
    loop.calc_outputs(0.0, x, {}, y);
    ASSERT_EQ(y[loop.output_index("saturated")], 0.0);
    loop.derivatives(0.0, x, {}, dx);
    const auto expected = spec_derivatives(1e-4 * 2 * std::numbers::pi / 0.005, x);
    // Identical formulas in another order: the largest products are ~1e5 (C_kopp Δφ/I), so
    // round-off stays below 1e-9 of them.
    for (int i = 0; i < 11; ++i) EXPECT_NEAR(dx[i], expected[i], 1e-9 * (1e5 + std::abs(expected[i]))) << i;
  }
}

TEST(ClosedLoopReferenceTest, SmallStepRisesIn34msWithoutOvershoot) {
  const StepRun run = run_step(step_of(1e-4));
  // Spec: rise 34.4 ms, 2 % settling 94.7 ms (printed to 0.1 ms, i.e. 0.15 %); 0.5 % keeps
  // a margin over the printing while still catching any parameter or wiring change.
  EXPECT_NEAR(run.metrics.rise_time, 34.4e-3, 0.005 * 34.4e-3);
  EXPECT_NEAR(run.metrics.settling_time, 94.7e-3, 0.005 * 94.7e-3);
  // "No overshoot": the peak stays below the target over 0.3 s (a 0.01 % overshoot would be
  // 10 nm; anything underdamped shows far more).
  EXPECT_LT(run.metrics.overshoot, 1e-4);
  EXPECT_EQ(run.last_saturated_time, 0.0);  // never leaves the linear range
}

TEST(ClosedLoopReferenceTest, LargeStepSaturatesAndDraws172A) {
  const StepRun run = run_step(step_of(5e-3));
  // Spec: rise 48.7 ms, settling 107.2 ms (0.1 ms printing; 0.5 % as above), ≈ 172 A
  // (printed to 1 A) with only the voltage limited, saturated for ≈ 20 ms (2 digits: ±1 ms).
  EXPECT_NEAR(run.metrics.rise_time, 48.7e-3, 0.005 * 48.7e-3);
  EXPECT_NEAR(run.metrics.settling_time, 107.2e-3, 0.005 * 107.2e-3);
  EXPECT_NEAR(run.peak_current, 172.0, 0.5);
  EXPECT_NEAR(run.last_saturated_time, 20e-3, 1e-3);
  EXPECT_LT(run.metrics.overshoot, 1e-4);
}

TEST(ClosedLoopReferenceTest, StepFiguresDoNotMoveWhenTheStepIsHalved) {
  for (double distance : {1e-4, 5e-3}) {
    const StepRun coarse = run_step(step_of(distance), step);
    const StepRun fine = run_step(step_of(distance), step / 2);
    // RK4 error ∝ h⁴: the difference bounds the coarse run's error. 1e-5 relative is 50×
    // below the tightest tolerance used above.
    EXPECT_NEAR(coarse.metrics.rise_time, fine.metrics.rise_time, 1e-5 * fine.metrics.rise_time);
    EXPECT_NEAR(coarse.metrics.settling_time, fine.metrics.settling_time, 1e-5 * fine.metrics.settling_time);
    EXPECT_NEAR(coarse.peak_current, fine.peak_current, 1e-5 * fine.peak_current);
  }
}

TEST(ClosedLoopReferenceTest, CurrentLimitHoldsTheArmatureCurrent) {
  ClosedLoopOptions o = step_of(5e-3);
  o.amplifier.current_limit.enabled = true;
  o.amplifier.current_limit.max_current = 30.0;
  const StepRun run = run_step(o, step, 0.5);
  // The clamp estimates the back-emf from the tacho rotor, which swings against the motor
  // rotor (455 Hz mode), and leaves L_a di/dt out: a few per cent over I_max at most.
  EXPECT_LT(run.peak_current, 30.0 * 1.05);
  EXPECT_GT(run.peak_current, 30.0 * 0.95);  // and it does reach the limit
  // Slower than voltage-limited (172 A), and the P position loop cannot brake hard enough
  // with 30 A: it overshoots (about 10 %) but still settles within the 0.5 s run.
  EXPECT_GT(run.metrics.rise_time, 48.7e-3);
  EXPECT_GT(run.metrics.overshoot, 0.0);
  EXPECT_LT(run.metrics.settling_time, 0.3);
}

double following_error_at_cruise_end(double feedforward) {
  ClosedLoopOptions o;
  // 40 mm at 100 mm/s, 1 m/s²: 0.3 s cruise (instead of the study's 0.1 s), so that the
  // position loop's transient (time constant 1/K_v = 25 ms) has died out, e^(−12).
  o.amplifier.setpoint = {SetpointKind::trapezoid, 0.0, 0.04, 0.1, 1.0};
  o.amplifier.velocity_feedforward = feedforward;
  ClosedLoopReference loop(o);
  const auto tr = testing::integrate_rk4(loop, 0.399, step, {}, 100);
  const auto& y = tr.outputs.back();
  return y[loop.output_index("position_reference")] - y[loop.output_index("slide_position")];
}

TEST(ClosedLoopReferenceTest, FollowingErrorAtConstantFeedIsVOverKv) {
  // The PI velocity loop has no steady-state error at constant speed, so the position loop
  // must supply ω = K_v Δφ: Δx = v/K_v = 2.5 mm. The spindle twist under the guide friction
  // (≈ 2e-6 rad) adds nanometres; 0.1 % covers the e^(−12) transient and the 455 Hz ripple.
  EXPECT_NEAR(following_error_at_cruise_end(0.0), 0.1 / 40, 1e-3 * 0.1 / 40);
  // Full velocity feed-forward supplies the speed without a position error.
  EXPECT_NEAR(following_error_at_cruise_end(1.0), 0.0, 1e-3 * 0.1 / 40);
}

TEST(ClosedLoopReferenceTest, SampledAmplifierShiftsTheStepAsTheCouplingStudyFound) {
  ClosedLoopOptions o = step_of(1e-4);
  const StepRun continuous = run_step(o);
  o.amplifier.sample_time = 1e-3;
  const StepRun sampled = run_step(o);
  // notes/coupling-facts.md: sampling at 1 ms changes rise by +0.7 % and settling by −3 %
  // (printed to 0.1 and 1 percentage point: ±0.05 and ±0.5).
  EXPECT_NEAR(sampled.metrics.rise_time / continuous.metrics.rise_time - 1, 0.007, 0.0005);
  EXPECT_NEAR(sampled.metrics.settling_time / continuous.metrics.settling_time - 1, -0.03, 0.005);
}

TEST(ClosedLoopReferenceTest, SampledResponseApproachesTheContinuousOneLinearlyInT) {
  auto position = [](double sample_time) {
    ClosedLoopOptions o = step_of(1e-4);
    o.amplifier.sample_time = sample_time;
    ClosedLoopReference loop(o);
    return testing::integrate_rk4(loop, 0.3, step).signal(loop.output_index("slide_position"));
  };
  const auto reference = position(0.0);
  auto rms_percent = [&](const std::vector<double>& x) {
    double sum = 0;
    for (std::size_t i = 0; i < x.size(); ++i) sum += (x[i] - reference[i]) * (x[i] - reference[i]);
    return 100 * std::sqrt(sum / x.size()) / 1e-4;
  };
  const double at_1ms = rms_percent(position(1e-3)), at_250us = rms_percent(position(2.5e-4));
  // The study: 0.7 % RMS at 1 ms, 0.17 % at 250 µs (its averaging window is not stated;
  // ±0.1 percentage point allows for it). A zero-order hold is first order in T: the
  // ratio must be near 4.
  EXPECT_NEAR(at_1ms, 0.7, 0.1);
  EXPECT_NEAR(at_250us, 0.17, 0.05);
  EXPECT_GT(at_1ms / at_250us, 3.0);
  EXPECT_LT(at_1ms / at_250us, 5.0);
}

}  // namespace
}  // namespace mechsim::models::nc

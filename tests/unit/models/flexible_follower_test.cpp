#include "mechsim/models/cam/flexible_follower.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mechsim/models/cam/press_cam.h"

namespace mechsim::models::cam {
namespace {

constexpr double pi = std::numbers::pi;

TEST(FlexibleFollower, EventsOfThePressCam) {
  const auto events = rest_to_rest_events(PressCam{}.law());
  ASSERT_EQ(events.size(), 2u);
  // The C1 + C2 rise is one event (they join at speed), the fall another.
  EXPECT_NEAR(rad_to_deg(events[0].start_rad), 26.25, 1e-12);
  EXPECT_NEAR(rad_to_deg(events[0].span_rad), 93.75, 1e-12);
  EXPECT_NEAR(events[0].end_lift_m, 0.025, 1e-15);
  EXPECT_NEAR(rad_to_deg(events[1].start_rad), 140.0, 1e-12);
  EXPECT_NEAR(rad_to_deg(events[1].span_rad), 70.0, 1e-12);
  EXPECT_EQ(critical_event_index(events), 1u);  // the fall is the shortest
  EXPECT_EQ(event_excitation(PressCam{}.law(), events[1], 0.0), 1.0);
  EXPECT_EQ(event_excitation(PressCam{}.law(), events[1], 1.0), 0.0);
}

TEST(FlexibleFollower, EventRunningThrough360Degrees) {
  const double d = deg_to_rad(1.0);
  // A rise that starts at 300° as C1 and ends at 60° as C2 is one event of 120°.
  const MotionLaw law({{SegmentType::half_cycloid_c2, 0.0, 60 * d, 0.008},
                       {SegmentType::full_cycloid, 120 * d, 90 * d, -0.010},
                       {SegmentType::half_cycloid_c1, 300 * d, 60 * d, 0.002}});
  const auto events = rest_to_rest_events(law);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_NEAR(rad_to_deg(events[0].start_rad), 120.0, 1e-12);
  EXPECT_NEAR(rad_to_deg(events[1].start_rad), 300.0, 1e-12);
  EXPECT_NEAR(rad_to_deg(events[1].span_rad), 120.0, 1e-12);
  EXPECT_NEAR(events[1].end_lift_m - events[1].start_lift_m, 0.010, 1e-15);
}

TEST(FlexibleFollower, StiffnessAndLambdaPrimeOfTheReport) {
  const double t1 = deg_to_rad(70.0) / pi;  // 0.3889 s at 30 rpm
  // The spec quotes 574.19 N/mm and 48.24 (±0.005).
  EXPECT_NEAR(follower_stiffness_for_lambda(9.38, 25.0, t1) / 1e3, 574.19, 0.005);
  EXPECT_NEAR(multi_rise_lambda(9.38, deg_to_rad(70.0)), 48.24, 0.005);
}

TEST(FlexibleFollower, SingleRiseOfThePressCamFall) {
  const MotionLaw law = PressCam{}.law();
  const auto event = rest_to_rest_events(law)[1];
  const auto r = single_rise(law, event, 9.38, 0.08);
  // Spec: max |γ − θ| ≈ 6.0e-3 during the fall (2 significant digits: ±0.05e-3).
  EXPECT_NEAR(r.max_error, 6.0e-3, 0.05e-3);
  EXPECT_GT(r.tau_max_error, 0.0);
  EXPECT_LT(r.tau_max_error, 1.0);
  // Residual vibration ≈ 2e-4 (1 significant digit: ±0.5e-4).
  EXPECT_NEAR(r.residual_amplitude, 2e-4, 0.5e-4);
  EXPECT_NEAR(r.max_residual, 2e-4, 0.5e-4);
  EXPECT_LE(r.max_residual, r.residual_amplitude);  // the free vibration only decays
  // Ã1 = Q/(2πλ)^3 with Q = (2π)² for the cycloid (the jerk jump at its end), exactly.
  EXPECT_EQ(r.approx_order, 3);
  EXPECT_NEAR(r.approx_q, 4 * pi * pi, 1e-9);
  EXPECT_NEAR(r.approx_residual_amplitude, 4 * pi * pi / std::pow(2 * pi * 9.38, 3), 1e-15);
  // Koster's approximation leaves out the start transient (decayed by e^{−2πζλ} ≈ 0.9 %)
  // and the next term of its expansion (relative size ≈ 1/(2πλ) ≈ 1.7 %): within 5 %.
  EXPECT_NEAR(r.residual_amplitude / r.approx_residual_amplitude, 1.0, 0.05);
}

TEST(FlexibleFollower, RungeKuttaStepIsConverged) {
  // Halving the step must not change the results beyond what the spec can resolve.
  const MotionLaw law = PressCam{}.law();
  const auto event = rest_to_rest_events(law)[1];
  const auto a = single_rise(law, event, 9.38, 0.08, 200);
  const auto b = single_rise(law, event, 9.38, 0.08, 400);
  // The residual envelope comes from the state at τ = 1: pure integration error, which
  // for RK4 at 200 steps per period is ~(2π/200)^4 ≈ 1e-6 of the amplitude per period at
  // worst; 1e-6 relative between the two steps.
  EXPECT_NEAR(a.residual_amplitude / b.residual_amplitude, 1.0, 1e-6);
  // Maxima are taken at step points: a sinusoid sampled N times per period peaks within
  // 1 − cos(π/N) ≈ 1.2e-4 (N = 200) of its true maximum.
  EXPECT_NEAR(a.max_error / b.max_error, 1.0, 1.3e-4);
  const auto m = multi_rise(law, 48.24, 0.08, 20, 200);
  const auto n = multi_rise(law, 48.24, 0.08, 20, 400);
  EXPECT_NEAR(m.max_error / n.max_error, 1.0, 1.3e-4);
  EXPECT_NEAR(m.max_dwell_error / n.max_dwell_error, 1.0, 1.3e-4);
}

TEST(FlexibleFollower, MultiRiseReachesPeriodicSteadyState) {
  const MotionLaw law = PressCam{}.law();
  const auto m = multi_rise(law, 48.24, 0.08, 20);
  // Damping removes a factor e^{−2πζλ'} = e^{−24} ≈ 4e-11 per cycle: by cycle 20 the
  // start transient is gone and consecutive cycles agree to rounding.
  EXPECT_LT(m.periodicity_error, 1e-12);
  EXPECT_EQ(m.cycles, 20);
  // Within the cycle, the fall behaves as the single-rise analysis predicts: the rise's
  // residual vibration (< 1e-4) has decayed by e^{−2πζλ·20/70} ≈ 0.26 over the 20° dwell,
  // so the two maxima differ by < 3e-5.
  const auto s = single_rise(law, rest_to_rest_events(law)[1], 9.38, 0.08);
  EXPECT_NEAR(m.max_error, s.max_error, 3e-5);
  EXPECT_GT(m.theta_max_error_rad, deg_to_rad(140.0));
  EXPECT_LT(m.theta_max_error_rad, deg_to_rad(210.0));
  // The largest dwell error is the fall's residual vibration.
  EXPECT_NEAR(m.max_dwell_error, s.max_residual, 3e-5);
}

TEST(FlexibleFollower, RefusesBadSettings) {
  const MotionLaw law = PressCam{}.law();
  const auto event = rest_to_rest_events(law)[1];
  EXPECT_THROW(single_rise(law, event, 0.0, 0.08), std::invalid_argument);
  EXPECT_THROW(single_rise(law, event, 9.38, 1.5), std::invalid_argument);
  EXPECT_THROW(multi_rise(law, 48.24, 0.08, 1), std::invalid_argument);
}

}  // namespace
}  // namespace mechsim::models::cam

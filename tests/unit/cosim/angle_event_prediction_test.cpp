// Run-time angle events (angle_event_prediction.h): the predicted instant against the
// closed-form solution of angle + speed tau + acceleration tau^2 / 2 = target, the turn
// counting of unwrapped angles, and the window (after, until] with crossings already landed.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "mechsim/cosim/angle_event_prediction.h"

namespace mechsim::cosim {
namespace {

constexpr double pi = std::numbers::pi;

TEST(AngleEventPrediction, AtConstantSpeedTheAngleIsReachedAtDistanceOverSpeed) {
  const ShaftMotion m{1.0, 0.0, 10.0, 0.0};
  const std::vector<double> events{pi / 2};
  const auto e = predict_angle_event(m, events, 1.0, 2.0);
  EXPECT_NEAR(e.t, 1.0 + (pi / 2) / 10.0, 1e-15);
  EXPECT_DOUBLE_EQ(e.target, pi / 2);
}

TEST(AngleEventPrediction, WithAccelerationTheQuadraticsRootIsTaken) {
  // theta = 0.2 + 5 tau + 20 tau^2 / 2 reaches 1 rad at tau = (-5 + sqrt(25 + 2 * 20 * 0.8)) / 20.
  const ShaftMotion m{0.0, 0.2, 5.0, 20.0};
  const std::vector<double> events{1.0};
  const auto e = predict_angle_event(m, events, 0.0, 1.0);
  EXPECT_NEAR(e.t, (-5.0 + std::sqrt(25.0 + 2 * 20 * 0.8)) / 20.0, 1e-15);
  // Decelerating: 0.2 + 5 tau - 10 tau^2 reaches 0.8 rad at tau = (5 - sqrt(25 - 4 * 10 * 0.6)) / 20.
  const ShaftMotion slowing{0.0, 0.2, 5.0, -20.0};
  const std::vector<double> near{0.8};
  EXPECT_NEAR(predict_angle_event(slowing, near, 0.0, 1.0).t, (5.0 - std::sqrt(25.0 - 4 * 10 * 0.6)) / 20.0, 1e-15);
  // ... and stops (at 0.2 + 25/40 = 0.825 rad) before 1 rad: no event.
  EXPECT_TRUE(std::isinf(predict_angle_event(slowing, events, 0.0, 1.0).t));
}

TEST(AngleEventPrediction, AnglesAreCountedOnTheUnwrappedShaftAngle) {
  // Three turns and 0.1 rad: the next 0.05 rad is in the fourth turn, the next 3 rad in the third.
  const ShaftMotion m{0.0, 6 * pi + 0.1, 1.0, 0.0};
  const std::vector<double> events{0.05, 3.0};
  const auto e = predict_angle_event(m, events, 0.0, 10.0);
  EXPECT_DOUBLE_EQ(e.target, 6 * pi + 3.0);
  EXPECT_NEAR(e.t, 2.9, 1e-12);
  const std::vector<double> only_first{0.05};
  EXPECT_DOUBLE_EQ(predict_angle_event(m, only_first, 0.0, 10.0).target, 8 * pi + 0.05);
}

TEST(AngleEventPrediction, OnlyCrossingsInsideTheWindowAndNotYetLandedCount) {
  const ShaftMotion m{0.0, 0.0, 1.0, 0.0};
  const std::vector<double> events{0.5, 1.0};
  // (after, until]: 0.5 rad is reached at 0.5 s, before `after`; 1 rad at 1 s.
  EXPECT_DOUBLE_EQ(predict_angle_event(m, events, 0.6, 2.0).t, 1.0);
  EXPECT_DOUBLE_EQ(predict_angle_event(m, events, 0.0, 1.0).t, 0.5);
  EXPECT_TRUE(std::isinf(predict_angle_event(m, events, 0.0, 0.4).t)) << "beyond `until`";
  // The crossing of 0.5 rad was landed on already: the next is 1 rad.
  EXPECT_DOUBLE_EQ(predict_angle_event(m, events, 0.0, 2.0, 0.5).t, 1.0);
  // A shaft at rest or turning back reaches nothing.
  EXPECT_TRUE(std::isinf(predict_angle_event({0.0, 0.0, 0.0, 0.0}, events, 0.0, 10.0).t));
  EXPECT_TRUE(std::isinf(predict_angle_event({0.0, 0.0, -1.0, 0.0}, events, 0.0, 10.0).t));
}

}  // namespace
}  // namespace mechsim::cosim

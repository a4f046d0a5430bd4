// The flexible follower in time (spec cam.md §5): integrated by SUNDIALS as the nodes do,
// driven by the press cam at constant speed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <vector>

#include "driven_follower.h"
#include "mechsim/models/cam/flexible_follower.h"
#include "mechsim/models/cam/force_analysis.h"
#include "mechsim/models/cam/geometry.h"
#include "mechsim/models/follower/flexible_follower_block.h"

#ifndef MRTOL
#define MRTOL 1e-11
#endif
namespace mechsim::models {
namespace {

constexpr double pi = std::numbers::pi;
using follower::FlexibleFollowerBlock;
using follower::FlexibleFollowerParams;

// k_f of the report: λ = 9.38 natural periods in the fall (70°) at 30 rpm.
double report_stiffness() {
  return cam::follower_stiffness_for_lambda(9.38, 25.0, cam::deg_to_rad(70.0) / pi);
}

// The press follower (mass, spring, loads) on the report's k_f with ζ = 0.08 in the contact.
FlexibleFollowerParams press_flexible(double stiffness_factor = 1.0, bool with_loads = true) {
  FlexibleFollowerParams p;
  p.follower = cam::PressCam{}.follower;
  if (!with_loads) p.follower.loads.clear();
  p.contact.stiffness_n_per_m = stiffness_factor * report_stiffness();
  p.contact.contact_damping_n_s_per_m = follower::damping_for_ratio(0.08, p.contact.stiffness_n_per_m, 25.0);
  return p;
}

solve::SolverOptions tolerances(solve::Method method, double rtol, double atol) {
  solve::SolverOptions o;
  o.method = method;
  o.rtol = rtol;
  o.atol = atol;
  return o;
}

double value(const BlockEvent& e, const char* name) {
  for (const auto& [n, v] : e.values)
    if (n == name) return v;
  ADD_FAILURE() << e.kind << " has no " << name;
  return NAN;
}

// Lift-offs and landings alternate, starting with a lift-off; each landing's flight is the
// time since its lift-off.
void expect_well_formed(const std::vector<BlockEvent>& events) {
  for (std::size_t i = 0; i < events.size(); ++i) {
    EXPECT_EQ(events[i].kind, i % 2 == 0 ? "lift_off" : "landing") << "event " << i;
    if (i % 2 == 1) {
      EXPECT_NEAR(value(events[i], "flight_duration_s"), events[i].t - events[i - 1].t, 1e-12);
      EXPECT_GT(value(events[i], "flight_duration_s"), 0.0);
    }
  }
}

TEST(FlexibleFollowerSimulation, MultiRiseAgreesWithTheVibrationAnalysis) {
  // Model (b) reduces exactly to the report's model (a) when the damper sits on the frame
  // (c = 2ζ√(k_f m)), the contact has no damper, there are no functional loads and no
  // spring stiffness, and a constant preload F0 keeps the contact closed: with
  // z = y + F0/k_f, m z̈ + c ż + k_f z = k_f S, i.e. γ'' + 2ζ(2πλ')γ' + (2πλ')² γ = (2πλ')² θ
  // with γ = z/S_max, τ = t/T. Same start (γ = θ(0) = 0 at rest), so the two agree at every
  // instant of all 20 cycles, not only in the steady state.
  const cam::PressCam press;
  const cam::MotionLaw law = press.law();
  const double kf = report_stiffness(), f0 = 125.0, s_max = 0.025, period = 2.0;
  FlexibleFollowerParams p;
  p.follower = {25.0, {0.0, f0}, {}};
  p.contact = {kf, 0.0, follower::damping_for_ratio(0.08, kf, 25.0)};
  const double lambda_prime = cam::multi_rise_lambda(9.38, cam::deg_to_rad(70.0));
  const int cycles = 20;
  const auto rk200 = cam::multi_rise(law, lambda_prime, 0.08, cycles, 200);
  const auto rk400 = cam::multi_rise(law, lambda_prime, 0.08, cycles, 400);

  // Simulate once, sampled at the τ of both RK4 results in the last cycle.
  std::vector<double> times;
  for (const auto* r : {&rk200, &rk400})
    for (const auto& s : r->samples) times.push_back((cycles - 1 + s.tau) * period);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  std::vector<std::pair<double, double>> gamma_at;  // (t, γ)
  double max_error = 0.0;
  FlexibleFollowerBlock b(p);
  const auto run = testing::drive_follower(
      b, testing::press_cam_shaft(pi), cycles * period, tolerances(solve::Method::cvode_adams, MRTOL, 1e-15), times,
      [&](double t, std::span<const double> x, std::span<const double> u) {
        const double gamma = (u[2] - x[0] + f0 / kf) / s_max;  // y = S − δ
        gamma_at.emplace_back(t, gamma);
        max_error = std::max(max_error, std::abs(gamma - u[2] / s_max));
      });
  ASSERT_EQ(b.lift_off_count(), 0) << "the preload must keep the contact closed for model (a) to apply";
  auto discrepancy = [&](const cam::MultiRiseResult& r) {
    double worst = 0.0;
    for (const auto& s : r.samples) {
      const double t = (cycles - 1 + s.tau) * period;
      auto it = std::lower_bound(gamma_at.begin(), gamma_at.end(), std::make_pair(t, -1e300));
      if (std::abs(it->second - s.gamma) > worst || std::fmod(s.tau, 0.05) < 0.0015) std::cout << "  tau " << s.tau << " g_cv " << it->second << " g_rk " << s.gamma << " theta " << s.excitation << " d " << it->second - s.gamma << "\n";
      worst = std::max(worst, std::abs(it->second - s.gamma));
    }
    return worst;
  };
  const double d200 = discrepancy(rk200), d400 = discrepancy(rk400);
  std::cout << "multi-rise: max |γ−θ| RK4 " << rk200.max_error << ", CVODE " << max_error
            << "; max |γ_CVODE − γ_RK4| at 200 steps/period " << d200 << ", at 400 " << d400
            << "; CVODE steps " << run.stats.steps << "\n";
  EXPECT_LT(d400, d200 / 8);
  EXPECT_LT(d200, 1e-6);
  EXPECT_NEAR(max_error, rk200.max_error, 2 * d200);
}

TEST(FlexibleFollowerSimulation, Explore) {
  for (double factor : {1e4})
  for (double zeta : {0.08, 0.3, 1.0})
   for (double rtol : {1e-6})
    for (bool loads : {false, true})
      for (auto method : {solve::Method::cvode_bdf, solve::Method::cvode_adams, solve::Method::arkode_erk}) {
        auto p = press_flexible(factor, loads);
        p.contact.contact_damping_n_s_per_m = follower::damping_for_ratio(zeta, p.contact.stiffness_n_per_m, 25.0);
        FlexibleFollowerBlock b(p);
        auto o = tolerances(method, rtol, 1e-9 * rtol / 1e-6 / factor);
        o.max_step = 5e-3;
        const auto run = testing::drive_follower(b, testing::press_cam_shaft(pi), 2.0, o);
        std::cout << "kf x" << factor << " loads " << loads << " zeta " << zeta << " rtol " << rtol << " method " << (method == solve::Method::cvode_bdf ? "BDF" : method == solve::Method::cvode_adams ? "Adams" : "ERK")
                  << ": steps " << run.stats.steps << " rhs " << run.stats.rhs_evals << " jac " << run.stats.jacobian_evals
                  << " etf " << run.stats.error_test_failures << " order " << run.stats.last_order << " events " << run.events.size() << "\n";
      }
}

}  // namespace
}  // namespace mechsim::models

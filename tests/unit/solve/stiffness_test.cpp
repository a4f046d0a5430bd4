// A stiff linear system: the implicit BDF method is limited by accuracy only, the explicit
// RK method by its stability region.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mechsim/solve/block_integrator.h"

namespace mechsim::solve {
namespace {

// x1' = -x1, x2' = lambda (x1 - x2): eigenvalues -1 and -lambda. x2 follows x1 after a
// fast transient of time constant 1/lambda.
class StiffPair final : public models::Block {
 public:
  explicit StiffPair(double lambda) : Block("test_stiff_pair"), lambda_(lambda) {
    declare_state("x1", "1");
    declare_state("x2", "1");
    declare_output("x2", "1");
  }
  void derivatives(double, std::span<const double> x, std::span<const double>,
                   std::span<double> dxdt) const override {
    dxdt[0] = -x[0];
    dxdt[1] = lambda_ * (x[0] - x[1]);
  }
  void calc_outputs(double, std::span<const double> x, std::span<const double>,
                    std::span<double> y) const override {
    y[0] = x[1];
  }

 private:
  double lambda_;
};

struct StiffRun {
  SolverStats stats;
  double x1, x2;
};

StiffRun integrate_one_second(Method method, double lambda) {
  StiffPair block(lambda);
  SolverOptions options;
  options.method = method;
  BlockIntegrator integrator(block, options, 0.0, std::vector<double>{1.0, 0.0});
  integrator.advance_to(1.0, {});
  return {integrator.stats(), integrator.state()[0], integrator.state()[1]};
}

TEST(Stiffness, BdfNeedsFewStepsWhereExplicitRungeKuttaIsStabilityLimited) {
  const double lambda = 1e4;
  const StiffRun bdf = integrate_one_second(Method::cvode_bdf, lambda);
  const StiffRun erk = integrate_one_second(Method::arkode_erk, lambda);

  // Both are still accurate at t = 1: x1 = e^-1, x2 = lambda/(lambda-1) (e^-1 - e^-lambda).
  // 50 * (rtol * |x| + atol), argued as for the decay test (contractive problem); the
  // e^-lambda term is below 1e-4000, i.e. zero.
  const double x1 = std::exp(-1.0), x2 = lambda / (lambda - 1.0) * std::exp(-1.0);
  for (const StiffRun* run : {&bdf, &erk}) {
    EXPECT_NEAR(run->x1, x1, 50 * (1e-6 * x1 + 1e-9));
    EXPECT_NEAR(run->x2, x2, 50 * (1e-6 * x2 + 1e-9));
  }

  // BDF resolves the transient (~1e-3 s) and then grows its step to what the smooth e^-t
  // needs at rtol 1e-6: on the order of a hundred steps. 300 is a generous ceiling.
  EXPECT_LT(bdf.stats.steps, 300);
  // An explicit RK step is stable only for h * lambda inside its stability region, whose
  // real extent is ~2.8 for 4th-order methods (2.79 for classical RK4): h < ~2.8e-4 s,
  // i.e. > ~3500 steps for 1 s however smooth the solution is. Hence at least ten times
  // the BDF count, and more than 2500 even if the table's interval reached 4.
  EXPECT_GT(erk.stats.steps, 10 * bdf.stats.steps)
      << "ERK " << erk.stats.steps << " steps vs BDF " << bdf.stats.steps;
  EXPECT_GT(erk.stats.steps, static_cast<long>(1.0 / (4.0 / lambda)));
  EXPECT_GT(bdf.stats.jacobian_evals, 0);  // the difference-quotient Jacobian was used
  EXPECT_EQ(erk.stats.jacobian_evals, 0);
}

}  // namespace
}  // namespace mechsim::solve

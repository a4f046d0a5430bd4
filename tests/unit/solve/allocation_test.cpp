// The integration loop must not allocate per step: counted through the global operator
// new of this test binary (SUNDIALS itself allocates with malloc, and only at set-up).
#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include <gtest/gtest.h>

#include "mechsim/solve/block_integrator.h"

namespace {
std::atomic<long> allocations{0};
}  // namespace

// Replacing the global allocation functions pairs malloc with free on purpose; GCC's
// heuristic only sees a new/free pair. noinline keeps every new and delete going through
// these symbols, which tools such as valgrind intercept as a pair.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

[[gnu::noinline]] void* operator new(std::size_t size) {
  ++allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace mechsim::solve {
namespace {

// A damped oscillator driven through its input: many steps, rhs and Jacobian evaluations.
class DrivenOscillator final : public models::Block {
 public:
  DrivenOscillator() : Block("test_driven_oscillator") {
    declare_input("force", "N", 0.0);
    declare_state("x", "m");
    declare_state("v", "m/s");
    declare_output("x", "m");
  }
  void derivatives(double, std::span<const double> x, std::span<const double> u,
                   std::span<double> dxdt) const override {
    dxdt[0] = x[1];
    dxdt[1] = u[0] - 100.0 * x[0] - 0.5 * x[1];
  }
  void calc_outputs(double, std::span<const double> x, std::span<const double>,
                    std::span<double> y) const override {
    y[0] = x[0];
  }
};

class AllocationEveryMethod : public ::testing::TestWithParam<Method> {};

INSTANTIATE_TEST_SUITE_P(Solve, AllocationEveryMethod,
                         ::testing::Values(Method::cvode_bdf, Method::cvode_adams,
                                           Method::arkode_erk, Method::arkode_dirk));

TEST_P(AllocationEveryMethod, NoHeapAllocationWhileIntegrating) {
  DrivenOscillator block;
  SolverOptions options;
  options.method = GetParam();
  BlockIntegrator integrator(block, options, 0.0, std::vector<double>{0.0, 0.0});
  const InputFunction force = [](double t, std::span<double> u) { u[0] = t < 0.5 ? 1.0 : -1.0; };
  integrator.advance_to(0.01, force);  // first steps and solver set-up outside the count

  const long before = allocations.load();
  for (int k = 2; k <= 100; ++k) {
    if (k == 50) integrator.mark_discontinuity();  // restarts must not allocate either
    integrator.advance_to(0.01 * k, force);
  }
  const long during = allocations.load() - before;
  EXPECT_EQ(during, 0);
  EXPECT_GT(integrator.stats().steps, 100);  // the loop did real work
}

}  // namespace
}  // namespace mechsim::solve

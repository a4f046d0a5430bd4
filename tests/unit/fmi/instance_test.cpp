// The binaries of the test FMUs driven through the importer: the lag against its closed form
// (co-simulation), its right-hand side (model exchange), and the run-time faults.
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <functional>

#include <gtest/gtest.h>

#include "fmu_files.h"
#include "mechsim/fmi/instance.h"

namespace mechsim::fmi {
namespace {

using test::test_fmu;

const Variable& variable(const FmuArchive& a, const std::string& name) {
  const Variable* v = a.description().find_variable(name);
  if (v == nullptr) throw std::runtime_error("test FMU lacks " + name);
  return *v;
}

std::string refusal_text(const std::function<void()>& f) {
  try {
    f();
  } catch (const FmuError& e) {
    return e.what();
  }
  return "(not refused)";
}

class LagCoSimulation : public ::testing::TestWithParam<const char*> {};

// T dy/dt = k u - y with k = 2, T = 0.05 s, y(0) = 0.5 V and u = 1 V up to 0.3 s, then
// -0.5 V, stepped every 1 ms to 0.6 s and compared at every step with
//   y(t) = k u + (y(t0) - k u) exp(-(t - t0)/T)   on each piece of constant u.
// Tolerance: the FMU integrates with RK4 substeps of 0.1 ms; its local error per substep is
// (h/T)^5/120 |y - k u| < 3e-16 V and the 6000 substeps' round-off at most ~6000 * 2.2e-16
// * 2 V = 3e-12 V; 1e-10 V leaves a margin, while a wrong parameter (T or k not reaching
// the FMU) or a step not taken misses by more than 1e-3 V.
TEST_P(LagCoSimulation, MatchesTheClosedForm) {
  const FmuArchive archive(FmuLabel{test_fmu(GetParam()), "lag"});
  auto fmu = FmuInstance::create(archive, InterfaceKind::co_simulation, "lag");
  const double k = 2.0, T = 0.05, y0 = 0.5, h = 1e-3;
  fmu->enter_initialization(0.0, 0.6);
  fmu->set_real(variable(archive, "k").value_reference, k);
  fmu->set_real(variable(archive, "T").value_reference, T);
  fmu->set_real(variable(archive, "y0").value_reference, y0);
  fmu->set_real(variable(archive, "u").value_reference, 1.0);
  fmu->exit_initialization();
  const Variable& y = variable(archive, "y");
  EXPECT_DOUBLE_EQ(fmu->get_finite_real(y), y0);

  double worst = 0.0;
  double y_switch = 0.0;  // y at the input's switch, the second piece's start value
  for (int n = 0; n < 600; ++n) {
    const double t = n * h;
    const double u = t < 0.3 - 1e-12 ? 1.0 : -0.5;
    if (n == 300) {
      y_switch = fmu->get_finite_real(y);
      fmu->set_real(variable(archive, "u").value_reference, u);
    }
    fmu->do_step(t, h);
    const double t1 = (n + 1) * h;
    const double expected = t1 <= 0.3 + 1e-12 ? k * 1.0 + (y0 - k * 1.0) * std::exp(-t1 / T)
                                              : k * u + (y_switch - k * u) * std::exp(-(t1 - 0.3) / T);
    worst = std::max(worst, std::abs(fmu->get_finite_real(y) - expected));
  }
  EXPECT_LT(worst, 1e-10);
  // y_switch itself against the closed form: the second piece does not start from a wrong value.
  EXPECT_NEAR(y_switch, k + (y0 - k) * std::exp(-0.3 / T), 1e-10);
  fmu->terminate();
}

INSTANTIATE_TEST_SUITE_P(TestFmus, LagCoSimulation, ::testing::Values("lag_fmi2_cs", "lag_fmi3_cs"));

class LagModelExchange : public ::testing::TestWithParam<const char*> {};

// The right-hand side the FMU hands out is the law's, at states and inputs mechsim sets;
// the event iteration after initialization settles at once (the lag has no events).
TEST_P(LagModelExchange, StatesAndDerivatives) {
  const FmuArchive archive(FmuLabel{test_fmu(GetParam()), "lag"});
  auto fmu = FmuInstance::create(archive, InterfaceKind::model_exchange, "lag");
  const double k = 2.0, T = 0.05, y0 = 0.5;
  fmu->enter_initialization(0.0, 1.0);
  fmu->set_real(variable(archive, "k").value_reference, k);
  fmu->set_real(variable(archive, "T").value_reference, T);
  fmu->set_real(variable(archive, "y0").value_reference, y0);
  fmu->exit_initialization();
  const DiscreteUpdate update = fmu->update_discrete_states();
  EXPECT_FALSE(update.terminate);
  EXPECT_FALSE(update.next_event_time_defined);
  fmu->enter_continuous_time_mode();
  ASSERT_EQ(archive.description().number_of_continuous_states, 1);
  double x = 0.0;
  fmu->get_continuous_states({&x, 1});
  EXPECT_EQ(x, y0);
  for (const auto& [state, input] : {std::pair{0.2, 1.5}, std::pair{-1.0, 0.0}, std::pair{3.0, -2.0}}) {
    fmu->set_time(0.1);
    const double xs[] = {state};
    fmu->set_continuous_states(xs);
    fmu->set_real(variable(archive, "u").value_reference, input);
    double dxdt = 0.0;
    fmu->get_derivatives({&dxdt, 1});
    EXPECT_DOUBLE_EQ(dxdt, (k * input - state) / T);
    EXPECT_EQ(fmu->get_finite_real(variable(archive, "y")), state);
    EXPECT_FALSE(fmu->completed_integrator_step());
  }
  fmu->terminate();
}

INSTANTIATE_TEST_SUITE_P(TestFmus, LagModelExchange, ::testing::Values("lag_fmi2_me", "lag_fmi3_me"));

struct FaultCase {
  const char* stem;
  const char* prefix;  // fmi2 / fmi3
};

class RunTimeFaults : public ::testing::TestWithParam<FaultCase> {
 protected:
  // The faulty FMU (an integrator dy/dt = u) with its fault armed past fault_time = 0.25 s.
  std::unique_ptr<FmuInstance> armed(const FmuArchive& archive, InterfaceKind kind, int fault) {
    auto fmu = FmuInstance::create(archive, kind, "bad");
    fmu->enter_initialization(0.0, 1.0);
    fmu->set_integer(variable(archive, "fault").value_reference, fault);
    fmu->set_real(variable(archive, "fault_time").value_reference, 0.25);
    fmu->set_real(variable(archive, "u").value_reference, 2.0);
    fmu->exit_initialization();
    return fmu;
  }
};

TEST_P(RunTimeFaults, StepErrorNamesFunctionStatusTimeAndTheFmuLog) {
  const std::string file = test_fmu(std::string(GetParam().stem) + "_cs");
  const FmuArchive archive(FmuLabel{file, "bad"});
  auto fmu = armed(archive, InterfaceKind::co_simulation, 1);
  fmu->do_step(0.0, 0.125);
  fmu->do_step(0.125, 0.125);
  EXPECT_DOUBLE_EQ(fmu->get_finite_real(variable(archive, "y")), 0.5);  // 2 V * 0.25 s
  EXPECT_EQ(fmu->get_integer(variable(archive, "fault").value_reference), 1);
  EXPECT_TRUE(fmu->get_boolean(variable(archive, "faulted").value_reference));
  const std::string p = GetParam().prefix;
  const std::string what = refusal_text([&] { fmu->do_step(0.25, 0.125); });
  EXPECT_NE(what.find("FMU '" + file + "' (participant 'bad')"), std::string::npos) << what;
  EXPECT_NE(what.find(p + "DoStep returned " + p + "Error at t = 0.25 s"), std::string::npos) << what;
  EXPECT_NE(what.find("injected fault"), std::string::npos) << what;
}

TEST_P(RunTimeFaults, DerivativeErrorInModelExchange) {
  const std::string file = test_fmu(std::string(GetParam().stem) + "_me");
  const FmuArchive archive(FmuLabel{file, "bad"});
  auto fmu = armed(archive, InterfaceKind::model_exchange, 1);
  fmu->update_discrete_states();
  fmu->enter_continuous_time_mode();
  double dxdt = 0.0;
  fmu->set_time(0.125);
  fmu->get_derivatives({&dxdt, 1});
  EXPECT_EQ(dxdt, 2.0);
  fmu->set_time(0.5);
  const std::string p = GetParam().prefix;
  const std::string what = refusal_text([&] { fmu->get_derivatives({&dxdt, 1}); });
  const std::string function = p == "fmi2" ? "fmi2GetDerivatives" : "fmi3GetContinuousStateDerivatives";
  EXPECT_NE(what.find(function + " returned " + p + "Error at t = 0.5 s"), std::string::npos) << what;
}

TEST_P(RunTimeFaults, NanOutputIsRefusedWithVariableAndTime) {
  const std::string file = test_fmu(std::string(GetParam().stem) + "_cs");
  const FmuArchive archive(FmuLabel{file, "bad"});
  auto fmu = armed(archive, InterfaceKind::co_simulation, 2);
  fmu->do_step(0.0, 0.125);
  EXPECT_DOUBLE_EQ(fmu->get_finite_real(variable(archive, "y")), 0.25);
  fmu->do_step(0.125, 0.125);
  const std::string what = refusal_text([&] { fmu->get_finite_real(variable(archive, "y")); });
  EXPECT_NE(what.find("FMU '" + file + "' (participant 'bad'): output 'y' is NaN at t = 0.25 s"), std::string::npos)
      << what;
}

// An FMU that aborts takes its process down: the importer cannot catch it, which is why an
// FMU runs in a node process of its own (its crash is a node crash). The dying child cannot
// remove its unpacked archive: it unpacks into a scratch TMPDIR that the parent removes.
TEST_P(RunTimeFaults, AbortingFmuEndsTheProcess) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const test::ScratchFolder scratch;
  const char* previous = std::getenv("TMPDIR");
  const std::string kept = previous ? previous : "";
  setenv("TMPDIR", scratch.path("").c_str(), 1);
  const FmuArchive archive(FmuLabel{test_fmu(std::string(GetParam().stem) + "_cs"), "bad"});
  auto fmu = armed(archive, InterfaceKind::co_simulation, 3);
  fmu->do_step(0.0, 0.25);
  EXPECT_EXIT(fmu->do_step(0.25, 0.125), ::testing::KilledBySignal(SIGABRT), "");
  if (previous) setenv("TMPDIR", kept.c_str(), 1); else unsetenv("TMPDIR");
}

INSTANTIATE_TEST_SUITE_P(TestFmus, RunTimeFaults,
                         ::testing::Values(FaultCase{"faulty_fmi2", "fmi2"}, FaultCase{"faulty_fmi3", "fmi3"}),
                         [](const auto& info) { return std::string(info.param.prefix); });

class BuildTimeFaults : public ::testing::TestWithParam<const char*> {};

TEST_P(BuildTimeFaults, MissingFunctionIsRefusedByName) {
  const std::string p = GetParam();
  const std::string file = test_fmu("faulty_no_do_step_" + p + "_cs");
  const FmuArchive archive(FmuLabel{file, "bad"});
  const std::string what = refusal_text([&] { FmuInstance::create(archive, InterfaceKind::co_simulation, "bad"); });
  const std::string platform = p == "fmi2" ? "linux64" : "x86_64-linux";
  EXPECT_NE(what.find("FMU '" + file + "' (participant 'bad'): its binary binaries/" + platform +
                      "/faulty_no_do_step.so lacks the function " + p + "DoStep"),
            std::string::npos)
      << what;
  EXPECT_NE(what.find("co-simulation"), std::string::npos) << what;
  // The same binary serves model exchange, which needs no DoStep.
  const FmuArchive me(FmuLabel{test_fmu("faulty_no_do_step_" + p + "_me"), "bad"});
  EXPECT_NO_THROW(FmuInstance::create(me, InterfaceKind::model_exchange, "bad"));
}

TEST_P(BuildTimeFaults, InstantiateReturningNullIsRefusedWithTheFmuLog) {
  const std::string p = GetParam();
  for (const auto& [kind, suffix, function] :
       {std::tuple{InterfaceKind::co_simulation, "_cs", p == "fmi2" ? "fmi2Instantiate" : "fmi3InstantiateCoSimulation"},
        std::tuple{InterfaceKind::model_exchange, "_me",
                   p == "fmi2" ? "fmi2Instantiate" : "fmi3InstantiateModelExchange"}}) {
    const std::string file = test_fmu("faulty_no_instance_" + p + suffix);
    const FmuArchive archive(FmuLabel{file, "bad"});
    const std::string what = refusal_text([&] { FmuInstance::create(archive, kind, "bad"); });
    EXPECT_NE(what.find("FMU '" + file + "' (participant 'bad'): " + std::string(function) + " returned NULL"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("this FMU never instantiates"), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(TestFmus, BuildTimeFaults, ::testing::Values("fmi2", "fmi3"));

}  // namespace
}  // namespace mechsim::fmi

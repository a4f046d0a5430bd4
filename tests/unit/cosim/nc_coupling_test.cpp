// The NC slide loop split in its three participants (config/scenes/nc_slide_loop_1ms.yaml:
// amplifier sampled at the macro step, identically in the reference) with the
// interface-Jacobian scheme on the stiff motor-spindle cut, run in process by the product's
// steppers against the monolithic reference: stable at H = 1 ms, accurate at 250 us (issue 6
// targets); and the linear-extrapolation compliant coupling diverging at 250 us, which the
// new scheme is there to beat. The DDS run of the same scene: tests/integration.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "in_process_run.h"
#include "mechsim/cosim/stepped_run.h"
#include "scene_files.h"

namespace mechsim::cosim {
namespace {

constexpr double kStep = 1e-4;  // m: the 0.1 mm position step

struct Figures {
  bool stable = false;
  double rms_error = NAN;    // RMS of the position error, fraction of the step
  double rise_error = NAN;   // relative rise-time error
  double final_error = NAN;  // final position error, fraction of the step
};

// The shipped 1 ms scene text with the cut's scheme replaced: "interface_jacobian" (as
// shipped) or "compliant" with the given reconstruction on both directions of the cut.
std::string nc_scene(const std::string& scheme, const std::string& reconstruction = "linear") {
  std::string text = testing::read_file(testing::shipped_scene("nc_slide_loop_1ms.yaml"));
  if (scheme == "interface_jacobian") return text;
  const std::string cut = "scheme: interface_jacobian, levels: 10,";
  text.replace(text.find(cut), cut.size(), "scheme: " + scheme + ",");
  const std::string conn = "  - {from: tacho, to: slide,\n";
  text.replace(text.find(conn), conn.size(),
               "  - {from: slide, to: tacho, order: jacobi, reconstruction: " + reconstruction + "}\n"
               "  - {from: tacho, to: slide, order: jacobi, reconstruction: " + reconstruction + ",\n");
  return text;
}

// The scene at macro step h (amplifier sampled at h too), with extra overrides. `step`: the
// position step the errors are relative to; 0 = where the reference settles (a sweep's
// overrides may change the setpoint).
Figures run_nc(const std::string& h, std::vector<std::string> overrides = {},
               const std::string& text = nc_scene("interface_jacobian"), double step = kStep) {
  overrides.push_back("time.step=" + h);
  overrides.push_back("participants.servo.params.sample_time=" + h);
  const std::string file = testing::write_scene(text);
  SteppedRun run(file, overrides);
  std::size_t slide = 0;
  while (run.plan().nodes()[slide].name() != "slide") ++slide;
  const int position = run.plan().nodes()[slide].block->output_index("slide_position");
  std::vector<double> x;
  run.on_publish = [&](std::size_t node, std::uint64_t, const std::vector<double>& y) {
    if (node == slide) x.push_back(y[static_cast<std::size_t>(position)]);
  };
  run.advance(run.steps());
  Figures f;
  if (run.diverged()) return f;
  auto ref_scene = std::make_unique<config::Scene>(config::load_scene(file, overrides));
  ScenePlan ref_plan = ScenePlan::build(*ref_scene);
  const ReferenceRun ref = run_reference(ref_plan);
  const auto& x_ref = ref.log.data[ref.log.column("slide.slide_position")];
  if (x.size() != x_ref.size()) throw std::logic_error("co-simulation and reference differ in length");
  double sum = 0;
  for (std::size_t k = 0; k < x.size(); ++k) sum += (x[k] - x_ref[k]) * (x[k] - x_ref[k]);
  f.stable = true;
  if (step == 0) step = x_ref.back();
  f.rms_error = std::sqrt(sum / static_cast<double>(x.size())) / step;
  const double hs = run.scene().time.step;
  const double rise = testing::rise_time(x, hs, step), rise_ref = testing::rise_time(x_ref, hs, step);
  f.rise_error = (rise - rise_ref) / rise_ref;
  f.final_error = (x.back() - x_ref.back()) / step;
  std::printf("  H = %-7s  RMS %.5f %%  rise %+.4f %%  final %+.5f %%\n", h.c_str(), 100 * f.rms_error,
              100 * f.rise_error, 100 * f.final_error);
  return f;
}

TEST(NcCoupling, InterfaceJacobianIsStableAtOneMillisecondAndAccurateAt250us) {
  // Issue 6 targets. 1 ms: stable (the divergence guard watches every output over 0.2 s:
  // the whole step response and settling); and the figures still close, since the
  // sampled reference itself changes by 0.7 % at 1 ms (coupling-facts.md) and the scheme
  // adds far less: 1 % bounds both.
  const Figures at_1ms = run_nc("1ms");
  ASSERT_TRUE(at_1ms.stable);
  EXPECT_LT(at_1ms.rms_error, 0.01);
  // 250 us: rise time and final position within 1 %, RMS position error below 1 % of the
  // step against the reference sampled identically.
  const Figures at_250us = run_nc("250us");
  ASSERT_TRUE(at_250us.stable);
  EXPECT_LT(std::abs(at_250us.rise_error), 0.01);
  EXPECT_LT(std::abs(at_250us.final_error), 0.01);
  EXPECT_LT(at_250us.rms_error, 0.01);
}

TEST(NcCoupling, LinearExtrapolationOfTheCompliantCouplingDivergesAt250us) {
  // The same loop with the shipped compliant coupling (partner angle and speed extrapolated
  // linearly): its limit with a sampled amplifier lies below 250 us (docs/nc-loop.md), so
  // the run must be stopped by the divergence guard: the case the new scheme is for.
  const std::string text = nc_scene("compliant", "linear");
  SteppedRun run(testing::write_scene(text), {"time.step=250us", "participants.servo.params.sample_time=250us"});
  run.advance(run.steps());
  EXPECT_TRUE(run.diverged().has_value());
}

// Measurement, not a check: MECHSIM_NC_SWEEP="1ms 500us 250us" prints the figures per step
// (MECHSIM_NC_SCHEME, MECHSIM_NC_SET: the scheme and one more override).
TEST(NcCoupling, Sweep) {
  const char* steps = std::getenv("MECHSIM_NC_SWEEP");
  if (!steps) GTEST_SKIP() << "set MECHSIM_NC_SWEEP to a list of macro steps";
  // MECHSIM_NC_SCHEME: interface_jacobian (default), or "compliant <reconstruction>".
  std::istringstream scheme(std::getenv("MECHSIM_NC_SCHEME") ? std::getenv("MECHSIM_NC_SCHEME") : "interface_jacobian");
  std::string name, reconstruction = "linear";
  scheme >> name >> reconstruction;
  std::vector<std::string> overrides;
  if (const char* o = std::getenv("MECHSIM_NC_SET")) {  // ';'-separated
    std::istringstream list(o);
    for (std::string one; std::getline(list, one, ';');) overrides.push_back(one);
  }
  std::istringstream in(steps);
  for (std::string h; in >> h;) {
    const Figures f = run_nc(h, overrides, nc_scene(name, reconstruction), 0.0);
    if (!f.stable) std::printf("  H = %-7s  diverged\n", h.c_str());
  }
}

}  // namespace
}  // namespace mechsim::cosim

// The NC slide loop split in its three participants (config/scenes/nc_slide_loop_1ms.yaml:
// amplifier sampled at the macro step, identically in the reference) with the
// interface-Jacobian scheme on the stiff motor-spindle cut, run in process by the product's
// steppers against the monolithic reference: stable at H = 1 ms, accurate at 250 us (issue 6
// targets); and the linear-extrapolation compliant coupling diverging at 250 us, which the
// new scheme is there to beat. The DDS run of the same scene: tests/integration.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <stdexcept>

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
// `text` with `from` replaced by `to`; throws naming `from` when the shipped scene no longer
// has it (a test that silently ran the shipped scheme would measure the wrong thing).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("nc_slide_loop_1ms.yaml has no '" + from + "'");
  return text.replace(at, from.size(), to);
}

// `levels`: the interface-Jacobian scheme with that many torque levels per step (the
// shipped scene has 10).
std::string nc_scene(const std::string& scheme, const std::string& reconstruction = "linear", int levels = 10) {
  std::string text = testing::read_file(testing::shipped_scene("nc_slide_loop_1ms.yaml"));
  const std::string cut = "scheme: interface_jacobian, levels: 10,";
  if (scheme == "interface_jacobian")
    return levels == 10 ? text : replaced(text, cut, "scheme: interface_jacobian, levels: " + std::to_string(levels) + ",");
  text = replaced(text, cut, "scheme: " + scheme + ",");
  return replaced(text, "  - {from: tacho, to: slide,\n",
                  "  - {from: slide, to: tacho, order: jacobi, reconstruction: " + reconstruction + "}\n"
                  "  - {from: tacho, to: slide, order: jacobi, reconstruction: " + reconstruction + ",\n");
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

// The interface-Jacobian accuracy bounds: each is the error measured here (docs/nc-loop.md,
// "Measured on the NC loop") times a stated margin, below what the scheme with fewer torque
// levels gives, so that a scheme that lost its `levels` (or fell back to one level, a
// first-order torque over the step) fails them (NcCoupling.FewerLevelsFailTheBoundsAtOneMillisecond).
// 1 ms: RMS 0.0023 % of the step, rise -0.019 %. Margin 2x on the RMS (the nodes' CVODE
// tolerance puts a floor of ~0.0004 % under it and moves it by a few 1e-4 %), 3x on the
// rise error; 2 levels give 0.0080 % / +0.037 %, 1 level 0.018 % / +0.14 %.
constexpr double kRmsAt1ms = 5e-5, kRiseAt1ms = 6e-4;
// 250 us: at the tolerance floor (RMS 0.0004 %, rise -0.0006 %, final below 0.001 %): 5x the
// floor. The issue-6 targets (1 % each) lie far above.
constexpr double kRmsAt250us = 2e-5, kRiseAt250us = 1e-4, kFinalAt250us = 5e-5;

TEST(NcCoupling, InterfaceJacobianIsStableAtOneMillisecondAndAccurateAt250us) {
  // 1 ms: stable (the divergence guard watches every output over 0.2 s: the whole step
  // response and settling).
  const Figures at_1ms = run_nc("1ms");
  ASSERT_TRUE(at_1ms.stable);
  EXPECT_LT(at_1ms.rms_error, kRmsAt1ms);
  EXPECT_LT(std::abs(at_1ms.rise_error), kRiseAt1ms);
  const Figures at_250us = run_nc("250us");
  ASSERT_TRUE(at_250us.stable);
  EXPECT_LT(std::abs(at_250us.rise_error), kRiseAt250us);
  EXPECT_LT(std::abs(at_250us.final_error), kFinalAt250us);
  EXPECT_LT(at_250us.rms_error, kRmsAt250us);
}

// What the bounds above guard: with 2 torque levels per step and with 1 the same run at
// 1 ms is stable but less accurate (docs/nc-loop.md: 0.0080 % and 0.018 % RMS), and each
// fails the shipped scheme's bound on the RMS or the rise time.
TEST(NcCoupling, FewerLevelsFailTheBoundsAtOneMillisecond) {
  const Figures ten = run_nc("1ms");
  const Figures two = run_nc("1ms", {}, nc_scene("interface_jacobian", "", 2));
  const Figures one = run_nc("1ms", {}, nc_scene("interface_jacobian", "", 1));
  ASSERT_TRUE(ten.stable && two.stable && one.stable);
  EXPECT_LT(ten.rms_error, two.rms_error);
  EXPECT_LT(two.rms_error, one.rms_error);
  for (const Figures* f : {&two, &one})
    EXPECT_TRUE(f->rms_error > kRmsAt1ms || std::abs(f->rise_error) > kRiseAt1ms)
        << "RMS " << f->rms_error << ", rise " << f->rise_error << " pass the 10-level bounds";
  // The table's figures, to a factor 2 (the tolerance floor and the run's length).
  EXPECT_NEAR(two.rms_error, 8.0e-5, 4e-5);
  EXPECT_NEAR(one.rms_error, 1.8e-4, 9e-5);
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

}  // namespace
}  // namespace mechsim::cosim

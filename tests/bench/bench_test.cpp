// `mechsim bench --quick` as a user runs it: real in-process runs, a DDS spot check through
// `mechsim launch`, the JSON rows, the observed orders and the PNG diagrams.
//
// Scene: nc_motor_bench (servo amplifier | motor + tachometer, both edges Jacobi with hold):
// smooth after the setpoint step at t = 0, no events, a decade of H around its 50 us step
// is stable, so the asymptotic orders of the Jacobi schemes show. (cam_press is not usable
// for orders: its rigid follower has no state and its load steps make the error
// jump-dominated, order 0.5 in RMS.)
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "run_command.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kMechsim = std::string(MECHSIM_BIN_DIR) + "/mechsim";
const std::string kScene = std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/nc_motor_bench.yaml";

CommandResult run_mechsim(const std::vector<std::string>& args, const std::string& log, double timeout_s) {
  std::vector<std::string> argv{kMechsim};
  argv.insert(argv.end(), args.begin(), args.end());
  return wait_for(spawn(argv, log), log, timeout_s);
}

class BenchQuick : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::string(fs::temp_directory_path() / ("mechsim-bench-test-" + std::to_string(::getpid())));
    fs::create_directories(*dir_);
    // H = 25, 50, 100, 200 us (half to four times the scene's step: the asymptotic range of
    // both schemes, measured) with cvode_bdf at rtol 1e-9 so that the node tolerance stays
    // far below the coupling error; the default --quick grid otherwise.
    result_ = new CommandResult(run_mechsim({"bench", kScene, "--quick", "--steps", "25 us,50 us,100 us,200 us", "--rtols",
                                             "1e-9", "--json", *dir_ + "/bench.json", "--plots", *dir_ + "/plots",
                                             "--work-dir", *dir_ + "/work", "--repeat", "2"},
                                            *dir_ + "/bench.log", 120));
    std::ifstream f(*dir_ + "/bench.json");
    if (f) doc_ = new json(json::parse(f, nullptr, false));
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    if (!::testing::Test::HasFailure()) fs::remove_all(*dir_, ec);
    delete dir_;
    delete result_;
    delete doc_;
  }
  static const json& doc() {
    static const json empty = json::object();
    return doc_ ? *doc_ : empty;
  }
  static const json* order_of(const std::string& scheme) {
    for (const auto& o : doc()["orders"])
      if (o["scheme"] == scheme) return &o;
    return nullptr;
  }
  static std::string* dir_;
  static CommandResult* result_;
  static json* doc_;
};
std::string* BenchQuick::dir_ = nullptr;
CommandResult* BenchQuick::result_ = nullptr;
json* BenchQuick::doc_ = nullptr;

TEST_F(BenchQuick, RunsAndWritesTheJson) {
  ASSERT_FALSE(result_->timed_out) << result_->output;
  ASSERT_EQ(result_->exit_code, 0) << result_->output;
  ASSERT_TRUE(doc_ && !doc_->is_discarded()) << "no JSON; output:\n" << result_->output;
  EXPECT_EQ(doc()["schema_version"], "1");
  EXPECT_TRUE(doc()["provenance"].contains("scene_sha256"));
  EXPECT_EQ(doc()["scene"], "nc_motor_bench");
  EXPECT_EQ(doc()["options"]["repeat"], 2) << "every run timed twice, the fastest kept";
  // The table and the progress were shown.
  EXPECT_NE(result_->output.find("observed order"), std::string::npos);
  EXPECT_NE(result_->output.find("[1/"), std::string::npos);
}

TEST_F(BenchQuick, EveryRowHasFiniteErrorsAboveTheReferenceError) {
  const json& rows = doc()["rows"];
  // Every scheme x 4 steps x (rtol 1e-6 and 1e-9), and --quick keeps at least the
  // zero-order-hold and linear Jacobi schemes (the scene ships jacobi/hold).
  // The adaptive rows (step_s null, a tolerance) come on top.
  const json& schemes = doc()["options"]["schemes"];
  ASSERT_GE(schemes.size(), 2u) << schemes.dump();
  std::size_t fixed = 0;
  for (const auto& r : rows) fixed += r["step_s"].is_number() ? 1 : 0;
  ASSERT_EQ(fixed, schemes.size() * 4 * 2);
  int numbers = 0;
  for (const auto& r : rows) {
    SCOPED_TRACE(r["scheme"].get<std::string>() + " H " + r["step_s"].dump() + " tolerance " + r.value("tolerance", json()).dump());
    // A decade around the scene's step is stable for these schemes (docs/accuracy.md).
    ASSERT_EQ(r["status"], "ok") << r["reason"];
    EXPECT_GT(r["solver_stats"]["steps"].get<long>(), 0);
    EXPECT_GT(r["wall_time_s"].get<double>(), 0.0);
    for (const auto& [name, s] : r["signals"].items()) {
      if (!s.value("computed", true)) continue;
      for (const char* m : {"rms", "max"}) {
        const json& value = s[std::string(m) + "_abs_error"];
        const double ref = s["reference_error"][std::string(m) + "_abs"].get<double>();
        if (value.is_null()) {
          // Refused as a number only when it is not above the reference's own error.
          EXPECT_TRUE(s["below_reference_accuracy"][m].get<bool>()) << name;
        } else {
          ++numbers;
          EXPECT_TRUE(std::isfinite(value.get<double>())) << name;
          EXPECT_GT(value.get<double>(), ref) << name << ": reported below the reference's error";
          EXPECT_FALSE(s["below_reference_accuracy"][m].get<bool>()) << name;
        }
      }
    }
  }
  EXPECT_GT(numbers, 0);
}

TEST_F(BenchQuick, AdaptivePointsAtEachQuickTolerance) {
  // --quick: tolerances 1e-2 and 1e-3 with the shipped scheme (jacobi/hold) and the best
  // fixed-H scheme at the scene's H; each measured against its own reference.
  std::map<std::string, std::map<double, long>> steps;  // scheme -> tolerance -> macro steps
  for (const auto& r : doc()["rows"]) {
    if (!r.contains("tolerance")) continue;
    SCOPED_TRACE(r["scheme"].get<std::string>() + " tolerance " + r["tolerance"].dump());
    EXPECT_EQ(r["scheme"].get<std::string>().rfind("adaptive ", 0), 0u);
    EXPECT_TRUE(r["step_s"].is_null());
    ASSERT_EQ(r["status"], "ok") << r["reason"];
    ASSERT_TRUE(r["error"]["max_rel"].is_number()) << r["error"].dump();
    EXPECT_TRUE(std::isfinite(r["error"]["max_rel"].get<double>()));
    EXPECT_GT(r["error"]["max_rel"].get<double>(), 0.0);
    EXPECT_GT(r["wall_time_s"].get<double>(), 0.0);
    EXPECT_EQ(r["reference"]["instants"].get<long>(), r["macro_steps"].get<long>() + 1);
    steps[r["scheme"]][r["tolerance"].get<double>()] = r["macro_steps"].get<long>();
  }
  ASSERT_TRUE(steps.count("adaptive jacobi/hold")) << "no adaptive row of the shipped scheme";
  for (const auto& [scheme, by_tol] : steps) {
    ASSERT_EQ(by_tol.size(), 2u) << scheme;
    // A tighter tolerance takes more macro steps.
    EXPECT_GT(by_tol.at(1e-3), by_tol.at(1e-2)) << scheme;
  }
  // The comparison with fixed H at equal wall time: a curve per adaptive scheme.
  const json& a = doc()["adaptive_vs_fixed"];
  ASSERT_EQ(a["curves"].size(), steps.size()) << a.dump();
  for (const auto& c : a["curves"]) {
    EXPECT_EQ(c["points"].size(), 2u);
    EXPECT_TRUE(c.contains("best_factor") && c.contains("target_5x_met") && c["rms"].contains("best_factor")) << c.dump();
    EXPECT_TRUE(c.contains("best_factor_at_equal_steps")) << c.dump();
    // The factor at equal steps is the same scheme's fixed-H error at the point's steps over
    // the point's error (null where the steps lie outside the fixed rows').
    for (const auto& p : c["points"]) {
      ASSERT_TRUE(p.contains("factor_at_equal_steps")) << p.dump();
      if (!p["factor_at_equal_steps"].is_number()) continue;
      EXPECT_NEAR(p["factor_at_equal_steps"].get<double>(),
                  p["fixed_error_same_scheme_at_equal_steps"].get<double>() / p["adaptive_error"].get<double>(), 1e-12)
          << p.dump();
    }
  }
  // Without `scales:` in the scene, the adaptive rows take each coupled field's reference range.
  for (const auto& r : doc()["rows"])
    if (r.contains("tolerance")) {
      EXPECT_EQ(r["scales_from"], "reference range") << r.dump();
      EXPECT_FALSE(r["scales"].empty()) << r.dump();
    }
  EXPECT_NE(result_->output.find("vs best fixed H at equal wall time"), std::string::npos) << result_->output;
  EXPECT_NE(result_->output.find("tol 1e-3"), std::string::npos) << result_->output;
}

TEST_F(BenchQuick, ObservedOrdersOfHoldAndLinearExtrapolation) {
  // Zero-order hold is first order, linear extrapolation second order in H (the two-mass
  // oscillator of coupling_order_test.cpp measures 1.04 and 2.00). Over a factor-8 range of H
  // the slope carries the pre-asymptotic terms of the closed loop (the setpoint step, the
  // 420 Hz tacho mode): +-0.3 on the first-order slope and +-0.4 on the second-order one
  // keep the two apart (an order-1 scheme cannot pass the 1.6 lower bound of order 2, nor
  // order 2 the 1.3 upper bound of order 1).
  const json* hold = order_of("jacobi/hold");
  const json* linear = order_of("jacobi/linear");
  ASSERT_TRUE(hold && linear);
  ASSERT_TRUE((*hold)["order"].is_number()) << hold->dump();
  ASSERT_TRUE((*linear)["order"].is_number()) << linear->dump();
  EXPECT_NEAR((*hold)["order"].get<double>(), 1.0, 0.3) << hold->dump();
  EXPECT_NEAR((*linear)["order"].get<double>(), 2.0, 0.4) << linear->dump();
}

TEST_F(BenchQuick, DdsSpotCheckGivesTheSameNumbers) {
  const json& checks = doc()["dds_checks"];
  ASSERT_GE(checks.size(), 1u);
  for (const auto& c : checks) {
    EXPECT_EQ(c["status"], "ok") << c.dump();
    // Results do not depend on timing (docs/protocol.md): the node logs are bit-identical.
    EXPECT_TRUE(c["outputs_identical"].get<bool>()) << c.dump();
    EXPECT_EQ(c["max_rms_abs_difference"].get<double>(), 0.0) << c.dump();
  }
}

TEST_F(BenchQuick, WritesThePngDiagrams) {
  for (const char* name : {"nc_motor_bench_work_precision.png", "nc_motor_bench_error_vs_step.png"}) {
    const std::string path = *dir_ + "/plots/" + name;
    std::ifstream f(path, std::ios::binary);
    ASSERT_TRUE(f) << path;
    char magic[4] = {};
    f.read(magic, 4);
    EXPECT_EQ(std::string(magic + 1, 3), "PNG") << path;
  }
}

TEST(BenchReference, AnErrorNotAboveTheReferencesOwnIsNeverANumber) {
  // cam_flat_face: the follower is kinematic, so the Gauss-Seidel ordering (cam first)
  // reproduces the reference exactly, and the reference's own error estimate is 0 too: an
  // error of 0 is not above the reference's error and must be refused, not reported as 0.
  // Zero-order hold Jacobi lags one step and must be reported as a number.
  const std::string dir = fs::temp_directory_path() / ("mechsim-bench-ref-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string scene = std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/cam_flat_face.yaml";
  auto r = run_mechsim({"bench", scene, "--quick", "--dds-checks", "0", "--schemes", "gauss_seidel/hold,jacobi/hold",
                        "--steps", "50 us,100 us", "--rtols", "1e-6", "--tolerances", "none", "--json", dir + "/b.json"},
                       dir + "/b.log", 60);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream f(dir + "/b.json");
  const json doc = json::parse(f);
  int refused = 0, measured = 0;
  for (const auto& row : doc["rows"]) {
    SCOPED_TRACE(row.dump().substr(0, 400));
    ASSERT_EQ(row["status"], "ok");
    if (row["scheme"] == "gauss_seidel/hold") {
      EXPECT_TRUE(row["error"]["rms_below_reference_accuracy"].get<bool>());
      EXPECT_TRUE(row["error"]["rms_rel"].is_null());
      EXPECT_TRUE(row["error"]["max_rel"].is_null());
      ++refused;
    } else {
      EXPECT_FALSE(row["error"]["rms_below_reference_accuracy"].get<bool>());
      EXPECT_GT(row["error"]["rms_rel"].get<double>(), 0.0);
      ++measured;
    }
  }
  EXPECT_EQ(refused, 2);
  EXPECT_EQ(measured, 2);  // and no adaptive row: --tolerances none
  EXPECT_TRUE(doc["adaptive_vs_fixed"]["curves"].empty());
  EXPECT_NE(r.output.find("<ref"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

TEST(BenchInput, RefusesBadInputWithAMessage) {
  const std::string dir = fs::temp_directory_path() / ("mechsim-bench-bad-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  auto r = run_mechsim({"bench", kScene, "--steps", "fast"}, dir + "/a.log", 30);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--steps"), std::string::npos) << r.output;
  r = run_mechsim({"bench", kScene, "--solvers", "euler"}, dir + "/b.log", 30);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("euler"), std::string::npos) << r.output;
  r = run_mechsim({"bench", kScene, "--tolerances", "1e-3,tight"}, dir + "/d.log", 30);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--tolerances"), std::string::npos) << r.output;
  r = run_mechsim({"bench", kScene, "--schemes", "no_such_scheme"}, dir + "/c.log", 30);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("no coupling scheme"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace mechsim::testing

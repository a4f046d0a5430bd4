// `mechsim motor-bode` and `mechsim slide-modes`: the JSON of the shipped CNC 200 scene
// against the spec's figures (spec/nc_slide.md §1–§2), where the data comes from
// (participants, connection coupling, design section), the refusals, and one end-to-end run
// of each command.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/models/nc/motor_tacho.h"
#include "motor_bode.h"
#include "nc_json.h"
#include "plot.h"
#include "slide_modes.h"

namespace mechsim::tools::nc_analyses {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string cnc200_scene = std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/cnc200_slide.yaml";

json bode_of(const std::string& scene, const std::vector<std::string>& overrides = {}) {
  return motor_bode_json(analyse_motor_bode(config::load_scene(scene, overrides), overrides));
}
json modes_of(const std::string& scene, const std::vector<std::string>& overrides = {}) {
  return slide_modes_json(analyse_slide_modes(config::load_scene(scene, overrides), overrides));
}
double d(const json& j) { return j.get<double>(); }

// A fresh directory for one test's files, removed afterwards.
class TempDir {
 public:
  explicit TempDir(const std::string& tag)
      : path_(fs::temp_directory_path() / ("mechsim-nc-analyses-" + tag + "-" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(file(name)) << text;
    return file(name);
  }

 private:
  fs::path path_;
};

// A time scene with the motor and the slide as participants, joined by the coupling.
std::string loop_scene(const std::string& slide_params_extra, const std::string& motor_params) {
  return "scene: nc_pair\n"
         "time: {start: 0 s, end: 0.01 s, step: 1 ms}\n"
         "participants:\n"
         "  motor:\n"
         "    type: tachometer\n"
         "    params: {" + motor_params + "}\n"
         "  spindle:\n"
         "    type: slide\n"
         "    params: {slide_mass: 235 kg" + slide_params_extra + "}\n"
         "connections:\n"
         "  - {from: motor, to: spindle, coupling: {stiffness: 11.5 kN m/rad, damping: 0.15 N m s/rad}}\n"
         "  - {from: spindle, to: motor}\n";
}

// ---------------------------------------------------------------------------------------
// motor-bode

// Spec §1: the identified set reproduces the measured DC gain and corner and the report's
// model resonance. The set was identified to these figures, quoted to 3 digits: ±1 %.
TEST(MotorBode, ReproducesTheSpecsFigures) {
  const json r = bode_of(cnc200_scene);
  EXPECT_EQ(r["source"]["key_path"], "design.motor");
  EXPECT_NEAR(d(r["dc_gain"]), 0.248, 0.01 * 0.248);
  EXPECT_NEAR(d(r["corner_hz"]), 17.0, 0.01 * 17.0);
  EXPECT_NEAR(d(r["resonance_hz"]), 455.0, 0.01 * 455.0);
  // "≈ +1.3 dB at b3 = 1e-2", quoted to 0.1 dB.
  EXPECT_NEAR(d(r["peak_db"]), 1.3, 0.1);
  // Damping of the pair, quoted as 0.013 (±0.0005).
  EXPECT_NEAR(d(r["damping_ratio"]), 0.013, 5e-4);
  // Stiffness ratio ≈ 38 and ≈ 109 on real parts (quoted to 2-3 digits: ±1.5 %).
  EXPECT_NEAR(d(r["stiffness_ratio"]), 38.0, 0.015 * 38.0);
  EXPECT_NEAR(d(r["real_part_ratio"]), 109.0, 0.015 * 109.0);
}

// The eigenvalues the spec lists (−106.59, −37.63 ± 2859.8j, −4096.9 1/s), to the digits given.
TEST(MotorBode, PolesAreTheSpecsEigenvalues) {
  const json p = bode_of(cnc200_scene)["poles"];
  ASSERT_EQ(p.size(), 4u);
  EXPECT_NEAR(d(p[0]["re"]), -106.59, 0.005);
  EXPECT_NEAR(d(p[1]["re"]), -37.63, 0.005);
  // The spec prints 2859.8 for 2859.749: one unit of the last digit.
  EXPECT_NEAR(std::abs(d(p[1]["im"])), 2859.8, 0.1);
  EXPECT_NEAR(d(p[1]["im"]), -d(p[2]["im"]), 1e-9);
  EXPECT_NEAR(d(p[3]["re"]), -4096.9, 0.05);
  EXPECT_NEAR(d(p[0]["f_hz"]), 16.96, 0.005);
  EXPECT_NEAR(d(p[3]["f_hz"]), 652.0, 0.5);
  EXPECT_NEAR(d(p[1]["f_hz"]), 455.2, 0.05);
  EXPECT_NEAR(d(p[0]["damping"]), 1.0, 1e-12);  // a real pole
}

// The JSON coefficients are those of the state equations: the polynomial ratio equals
// C (sI − A)⁻¹ B at any s (round-off only: 1e-9 relative), and n0 carries the back-emf
// term c·k that the report's appendix drops.
TEST(MotorBode, CoefficientsMatchTheStateEquations) {
  const json c = bode_of(cnc200_scene)["coefficients"];
  const models::nc::MotorTachoParams p{};  // the scene's design.motor is the spec's identified set
  EXPECT_NEAR(d(c["n0"]), p.torque_constant * p.shaft_stiffness, 1e-12 * d(c["n0"]));
  EXPECT_NEAR(d(c["m0"]) / d(c["n0"]), p.tacho_constant / p.torque_constant, 1e-12);
  const auto ss = models::nc::state_space(p);
  for (double f : {1.0, 17.0, 455.0, 3000.0}) {
    const std::complex<double> s(0, 2 * M_PI * f);
    const Eigen::Matrix4cd resolvent = (s * Eigen::Matrix4cd::Identity() - ss.a.cast<std::complex<double>>()).inverse();
    const std::complex<double> exact = (ss.c.cast<std::complex<double>>() * resolvent * ss.b.col(0).cast<std::complex<double>>())(0);
    const std::complex<double> ratio = (d(c["m1"]) * s + d(c["m0"])) /
                                       ((((d(c["n4"]) * s + d(c["n3"])) * s + d(c["n2"])) * s + d(c["n1"])) * s + d(c["n0"]));
    EXPECT_NEAR(std::abs(ratio - exact) / std::abs(exact), 0.0, 1e-9) << f << " Hz";
  }
}

// The report's approximations (3)–(5) are "all within 5 % of the exact poles here".
TEST(MotorBode, ApproximationsAreWithinFivePercent) {
  const json r = bode_of(cnc200_scene);
  EXPECT_NEAR(d(r["approx_s1_hz"]), d(r["exact_s1_hz"]), 0.05 * d(r["exact_s1_hz"]));
  EXPECT_NEAR(d(r["approx_s2_hz"]), d(r["exact_s2_hz"]), 0.05 * d(r["exact_s2_hz"]));
  EXPECT_NEAR(d(r["approx_f0_hz"]), d(r["exact_f0_hz"]), 0.05 * d(r["exact_f0_hz"]));
  ASSERT_EQ(r["approximations"].size(), 3u);
  for (const auto& a : r["approximations"]) EXPECT_LT(std::abs(d(a["error_percent"])), 5.0) << a["name"];
}

// Spec §1: the correct model gives about 17.5 dB at b3 = 1e-4 and −17 dB at 1e-1 (quoted
// to about half a dB), +1.3 dB at 1e-2; the damping never moves the DC gain.
TEST(MotorBode, ShaftDampingVariants) {
  const json r = bode_of(cnc200_scene);
  const json& v = r["b3_variants"];
  ASSERT_EQ(v.size(), 3u);
  EXPECT_DOUBLE_EQ(d(v[0]["b3"]), 1e-4);
  EXPECT_NEAR(d(v[0]["peak_db"]), 17.5, 0.5);
  EXPECT_NEAR(d(v[1]["peak_db"]), 1.3, 0.1);
  EXPECT_NEAR(d(v[2]["peak_db"]), -17.0, 0.5);
  // Real-part ratio ≈ 700 with b3 = 1e-4 (quoted to 1-2 digits: ±5 %).
  EXPECT_NEAR(d(v[0]["real_part_ratio"]), 700.0, 0.05 * 700.0);
  for (const auto& e : v) EXPECT_NEAR(d(e["dc_gain"]), d(r["dc_gain"]), 1e-12);
  // More damping, a lower peak.
  EXPECT_GT(d(v[0]["peak_db"]), d(v[1]["peak_db"]));
  EXPECT_GT(d(v[1]["peak_db"]), d(v[2]["peak_db"]));
}

// Default load: the slide drive train as one rigid inertia, I_kopp + I_sp + I_slide, the
// same number slide-modes derives. A heavier rotor lowers the corner and the resonance and
// leaves the DC gain (α/c) alone; approximation (5) with I1 + J still holds within 5 %.
TEST(MotorBode, LoadInertiaDefaultsToTheRigidDriveTrain) {
  const json r = bode_of(cnc200_scene);
  const json& load = r["load_inertia"];
  EXPECT_NEAR(d(load["inertia_kgm2"]), d(modes_of(cnc200_scene)["derived"]["rigid_inertia_kgm2"]), 1e-15);
  EXPECT_NEAR(d(load["rotor_inertia_with_load_kgm2"]), 1.2e-3 + d(load["inertia_kgm2"]), 1e-15);
  EXPECT_NEAR(d(load["dc_gain"]), d(r["dc_gain"]), 1e-12);
  EXPECT_LT(d(load["corner_hz"]), d(r["corner_hz"]));
  EXPECT_LT(d(load["resonance_hz"]), d(r["resonance_hz"]));
  EXPECT_NEAR(d(load["approx_f0_hz"]), d(load["natural_frequency_hz"]), 0.05 * d(load["natural_frequency_hz"]));

  const json given = bode_of(cnc200_scene, {"design.motor_bode.load_inertia=1e-3 kg m^2"});
  EXPECT_DOUBLE_EQ(d(given["load_inertia"]["inertia_kgm2"]), 1e-3);
  EXPECT_EQ(given["load_inertia"]["source"], "design.motor_bode.load_inertia");
}

// A tachometer participant supplies the motor: four times the shaft stiffness doubles the
// resonance (approximation (5) exactly, the exact pair within 1 %: b3 shifts it slightly).
TEST(MotorBode, ReadsTheTachometerParticipant) {
  TempDir dir("motor");
  const json base = bode_of(dir.write("base.yaml", loop_scene("", "")));
  const json stiff = bode_of(dir.write("stiff.yaml", loop_scene("", "shaft_stiffness: 5088.92 N m/rad")));
  EXPECT_EQ(stiff["source"]["kind"], "participant");
  EXPECT_EQ(stiff["source"]["key_path"], "participants.motor.params");
  EXPECT_NEAR(d(stiff["approx_f0_hz"]) / d(base["approx_f0_hz"]), 2.0, 1e-9);
  EXPECT_NEAR(d(stiff["exact_f0_hz"]) / d(base["exact_f0_hz"]), 2.0, 0.01 * 2.0);
}

// Motor data in both places is ambiguous: refused at the design section's key.
TEST(MotorBode, RefusesMotorDataInParticipantAndDesign) {
  TempDir dir("ambiguous");
  const std::string scene =
      dir.write("s.yaml", loop_scene("", "") + "design:\n  motor: {shaft_stiffness: 1000 N m/rad}\n");
  try {
    bode_of(scene);
    FAIL() << "motor data in two places was accepted";
  } catch (const config::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "design.motor");
  }
}

// ---------------------------------------------------------------------------------------
// slide-modes

// Spec §2 with the report's I_slide = 2.1e-4 kg m²: model 1 520 Hz, model 3 786 Hz at the
// mid position with N = 3 (report figures; ±2 %: the report rounds its inputs).
TEST(SlideModes, ReproducesTheReportsFrequencies) {
  const json r = modes_of(cnc200_scene);
  EXPECT_EQ(r["source"]["key_path"], "participants.slide.params");
  EXPECT_NEAR(d(r["inputs"]["slide_inertia_kgm2"]), 2.1e-4, 1e-15);
  // I_sp = 1.73e-3 kg m², C_sp = 7.86e3 N m/rad as quoted (3 digits: ±0.5 %).
  EXPECT_NEAR(d(r["derived"]["spindle_inertia_kgm2"]), 1.73e-3, 0.005 * 1.73e-3);
  EXPECT_NEAR(d(r["derived"]["spindle_stiffness_nm_per_rad"]), 7.86e3, 0.005 * 7.86e3);
  EXPECT_NEAR(d(r["derived"]["coupling_equivalent_length_mm"]), 510.0, 0.01 * 510.0);  // "≈ 0.51 m"
  EXPECT_NEAR(d(r["f0_model1_hz"]), 520.0, 0.02 * 520.0);
  EXPECT_DOUBLE_EQ(d(r["slide_position_mm"]), 750.0);
  EXPECT_EQ(r["f0_model3_ritz_shapes"], 3);
  EXPECT_NEAR(d(r["f0_model3_hz"]), 786.0, 0.02 * 786.0);
  EXPECT_NEAR(d(r["f0_model3_converged_hz"]), 786.0, 0.02 * 786.0);
}

// Model 2 against Klotter's two-mass formula for the grounded chain
// I1 I2 ω⁴ − (I1 C2 + I2 (C1 + C2)) ω² + C1 C2 = 0 (round-off only: 1e-9 relative).
TEST(SlideModes, GroundedChainMatchesKlottersFormula) {
  const json r = modes_of(cnc200_scene);
  const double i1 = d(r["derived"]["model1_drive_end_inertia_kgm2"]), i2 = d(r["derived"]["model1_slide_end_inertia_kgm2"]);
  const double c1 = d(r["inputs"]["coupling_stiffness_nm_per_rad"]), c2 = d(r["derived"]["spindle_stiffness_nm_per_rad"]);
  const double b = (i1 * c2 + i2 * (c1 + c2)) / (i1 * i2), c = c1 * c2 / (i1 * i2);
  const double root = std::sqrt(b * b / 4 - c);
  const double f1 = std::sqrt(b / 2 - root) / (2 * M_PI), f2 = std::sqrt(b / 2 + root) / (2 * M_PI);
  ASSERT_EQ(r["f0_model2_hz"].size(), 2u);
  EXPECT_NEAR(d(r["f0_model2_hz"][0]), f1, 1e-9 * f1);
  EXPECT_NEAR(d(r["f0_model2_hz"][1]), f2, 1e-9 * f2);
}

// Both discretisations of model 3 converge to one value: Ritz from above (upper bounds,
// falling with N), the lumped-mass chain from below at second order; their finest values
// agree to 1e-4 (Ritz at 64 shapes is about 2e-5 off, torsion_shaft.h: ~1/N).
TEST(SlideModes, RitzAndFiniteElementsConverge) {
  const json r = modes_of(cnc200_scene);
  const json& ritz = r["model3_convergence"]["ritz"];
  const json& fe = r["model3_convergence"]["fe"];
  ASSERT_GE(ritz.size(), 3u);
  ASSERT_GE(fe.size(), 3u);
  for (std::size_t i = 1; i < ritz.size(); ++i) EXPECT_LE(d(ritz[i]["f0_hz"]), d(ritz[i - 1]["f0_hz"])) << i;
  for (std::size_t i = 1; i < fe.size(); ++i) EXPECT_GE(d(fe[i]["f0_hz"]), d(fe[i - 1]["f0_hz"])) << i;
  const double converged = d(r["f0_model3_converged_hz"]);
  EXPECT_NEAR(d(ritz.back()["f0_hz"]), converged, 1e-4 * converged);
  EXPECT_GE(d(ritz.back()["f0_hz"]), converged);
  // Observed order of the chain from its three finest meshes (halved each time): 2 ± 0.1.
  const std::size_t n = fe.size();
  const double order = std::log2((d(fe[n - 2]["f0_hz"]) - d(fe[n - 3]["f0_hz"])) / (d(fe[n - 1]["f0_hz"]) - d(fe[n - 2]["f0_hz"])));
  EXPECT_NEAR(order, 2.0, 0.1);
  EXPECT_NEAR(d(r["f0_model3_extrapolated_hz"]), converged, 1e-5 * converged);
}

// f0(x) over the whole spindle peaks "near the middle", at the node of the first free–free
// mode of the equivalent shaft, where the slide inertia drops out: the converged sweep's
// maximum lies within one grid step (25 mm) of x = (l − l_eq)/2 and matches the closed form
// sqrt(G/ρ)/(2(l_eq + l)) there to 1e-4 (FE error at 256 elements ~1e-5, plus being up to
// 12.5 mm off the node on a flat maximum).
TEST(SlideModes, PositionSweepPeaksAtTheModeNode) {
  const json r = modes_of(cnc200_scene);
  const json& sweep = r["f0_vs_position"];
  ASSERT_EQ(sweep.size(), 61u);
  EXPECT_DOUBLE_EQ(d(sweep.front()["position_mm"]), 0.0);
  EXPECT_DOUBLE_EQ(d(sweep.back()["position_mm"]), 1500.0);
  const json& node = r["first_mode_node"];
  ASSERT_FALSE(node.is_null());
  EXPECT_NEAR(d(r["f0_max"]["position_mm"]), d(node["position_mm"]), 25.0);
  EXPECT_NEAR(d(r["f0_max"]["f0_converged_hz"]), d(node["f0_hz"]), 1e-4 * d(node["f0_hz"]));
  // The report's mid position lies beyond the peak: lower than the maximum.
  EXPECT_LT(d(r["f0_model3_converged_hz"]), d(r["f0_max"]["f0_converged_hz"]));
}

// The diameter sweep spans the report's 31–39 mm and passes exactly through the nominal case.
TEST(SlideModes, DiameterSweepContainsTheNominalCase) {
  const json r = modes_of(cnc200_scene);
  const json& sweep = r["f0_vs_diameter"];
  ASSERT_EQ(sweep.size(), 9u);
  EXPECT_NEAR(d(sweep.front()["diameter_mm"]), 31.0, 1e-9);
  EXPECT_NEAR(d(sweep.back()["diameter_mm"]), 39.0, 1e-9);
  const json& nominal = sweep[4];
  EXPECT_NEAR(d(nominal["diameter_mm"]), 35.0, 1e-9);
  EXPECT_NEAR(d(nominal["f0_model1_hz"]), d(r["f0_model1_hz"]), 1e-9);
  EXPECT_NEAR(d(nominal["f0_model3_hz"]), d(r["f0_model3_hz"]), 1e-9);
  // The sweep's chain has 256 elements, the convergence study's finest 1024: O(h²) puts the
  // coarser one 15/16 of its own error, about 6e-6, below (see the convergence list).
  EXPECT_NEAR(d(nominal["f0_model3_converged_hz"]), d(r["f0_model3_converged_hz"]), 2e-5 * d(r["f0_model3_converged_hz"]));
  // Only the spindle changes: the coupling's stand-in piece keeps the nominal equivalent
  // length at every diameter, and f0 rises as the spindle thickens (spec §2).
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    EXPECT_NEAR(d(sweep[i]["coupling_equivalent_length_mm"]), d(r["derived"]["coupling_equivalent_length_mm"]), 1e-9);
    if (i > 0) EXPECT_GT(d(sweep[i]["f0_model3_converged_hz"]), d(sweep[i - 1]["f0_model3_converged_hz"]));
  }
}

// In a loop scene the coupling spring belongs to the connection: slide-modes uses it, and a
// different coupling_stiffness in the slide's params is refused at that key.
TEST(SlideModes, CouplingStiffnessComesFromTheConnection) {
  TempDir dir("coupling");
  const json r = modes_of(dir.write("s.yaml", loop_scene("", "")));
  EXPECT_EQ(r["coupling_stiffness_source"]["kind"], "connection");
  EXPECT_EQ(r["coupling_stiffness_source"]["key_path"], "connections[0].coupling");
  EXPECT_DOUBLE_EQ(d(r["inputs"]["coupling_stiffness_nm_per_rad"]), 11.5e3);
  EXPECT_EQ(r["inputs"]["slide_inertia_from"], "m s^2/(4 pi^2)");
  try {
    modes_of(dir.write("bad.yaml", loop_scene(", coupling_stiffness: 23 kN m/rad", "")));
    FAIL() << "a coupling stiffness differing from the connection's was accepted";
  } catch (const config::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "participants.spindle.params.coupling_stiffness");
  }
}

// Without a slide participant the data comes from design.slide (its keys only).
TEST(SlideModes, ReadsDesignSlide) {
  TempDir dir("design");
  const std::string scene = dir.write("s.yaml", loop_scene("", "") + "design:\n  slide: {slide_inertia: 2.1e-4 kg m^2}\n");
  try {
    modes_of(scene);
    FAIL() << "slide data in two places was accepted";
  } catch (const config::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "design.slide");
  }
  const std::string only_design = dir.write("d.yaml",
                                            "scene: d\ntime: {start: 0 s, end: 1 ms, step: 1 ms}\n"
                                            "participants:\n  motor: {type: tachometer}\n"
                                            "design:\n  slide: {slide_inertia: 2.1e-4 kg m^2, variant: rigid}\n");
  try {
    modes_of(only_design);
    FAIL() << "a time-run key in design.slide was accepted";
  } catch (const config::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "design.slide.variant");
  }
  const json r = modes_of(dir.write("ok.yaml",
                                    "scene: d\ntime: {start: 0 s, end: 1 ms, step: 1 ms}\n"
                                    "participants:\n  motor: {type: tachometer}\n"
                                    "design:\n  slide: {slide_inertia: 2.1e-4 kg m^2}\n"));
  EXPECT_EQ(r["source"]["key_path"], "design.slide");
  EXPECT_NEAR(d(r["f0_model1_hz"]), d(modes_of(cnc200_scene)["f0_model1_hz"]), 1e-9);
}

// Refusals of the design section name the key path.
TEST(NcDesignSettings, RefusesBadInputWithTheKeyPath) {
  const auto key_path_of = [](const std::vector<std::string>& overrides) {
    try {
      modes_of(cnc200_scene, overrides);
    } catch (const config::ConfigError& e) {
      return e.key_path();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(key_path_of({"design.slide_modes.ritz_shapez=4"}), "design.slide_modes.ritz_shapez");
  EXPECT_EQ(key_path_of({"design.slide_modes.ritz_shapes=1"}), "design.slide_modes.ritz_shapes");
  EXPECT_EQ(key_path_of({"design.slide_modes.slide_position=2 m"}), "design.slide_modes.slide_position");
  EXPECT_EQ(key_path_of({"design.slide_modes.slide_position=20 deg"}), "design.slide_modes.slide_position");
  EXPECT_EQ(key_path_of({"design.motor_bode.frequency_range=10 Hz"}), "design.motor_bode.frequency_range");
  EXPECT_EQ(key_path_of({"design.motor.shaft_stiffness=-1 N m/rad"}), "design.motor.shaft_stiffness");
  EXPECT_EQ(key_path_of({"design.slide_modes.slide_position=1200 mm"}), "(accepted)");
}

// ---------------------------------------------------------------------------------------
// The commands end to end

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(NcAnalysesCommand, MotorBodeWritesJsonAndPlots) {
  const std::string mechsim = std::string(MECHSIM_BIN_DIR) + "/mechsim";
  ASSERT_TRUE(fs::exists(mechsim)) << mechsim;
  TempDir dir("bode-cli");
  const std::string command = mechsim + " motor-bode " + cnc200_scene + " --json " + dir.file("bode.json") +
                              " --plots " + dir.file("plots") + " > " + dir.file("out.txt") + " 2>&1";
  ASSERT_EQ(run(command), 0) << command << "\n" << read_file(dir.file("out.txt"));
  const json r = json::parse(read_file(dir.file("bode.json")));
  EXPECT_EQ(r["command"], "motor-bode");
  EXPECT_NEAR(d(r["resonance_hz"]), 455.0, 0.01 * 455.0);
  if (!plot::gnuplot_available()) GTEST_SKIP() << "gnuplot not installed: PNGs not checked";
  for (const char* png : {"bode.png", "bode_b3_variants.png", "bode_load_inertia.png"})
    EXPECT_GT(fs::file_size(dir.file("plots") + "/" + png), 0u) << png;
}

// Also checks that --set design.* reaches the design section (SceneArgs alone would send
// it to a participant named 'design').
TEST(NcAnalysesCommand, SlideModesWritesJsonAndPlots) {
  const std::string mechsim = std::string(MECHSIM_BIN_DIR) + "/mechsim";
  ASSERT_TRUE(fs::exists(mechsim)) << mechsim;
  TempDir dir("modes-cli");
  const std::string command = mechsim + " slide-modes " + cnc200_scene + " --json " + dir.file("modes.json") +
                              " --plots " + dir.file("plots") + " --set 'design.slide_modes.position_points=31' > " +
                              dir.file("out.txt") + " 2>&1";
  ASSERT_EQ(run(command), 0) << command << "\n" << read_file(dir.file("out.txt"));
  const json r = json::parse(read_file(dir.file("modes.json")));
  EXPECT_EQ(r["command"], "slide-modes");
  EXPECT_EQ(r["f0_vs_position"].size(), 31u);
  EXPECT_NEAR(d(r["f0_model3_hz"]), 786.0, 0.02 * 786.0);
  if (!plot::gnuplot_available()) GTEST_SKIP() << "gnuplot not installed: PNGs not checked";
  for (const char* png : {"f0_vs_position.png", "f0_vs_diameter.png", "model3_convergence.png"})
    EXPECT_GT(fs::file_size(dir.file("plots") + "/" + png), 0u) << png;
}

TEST(NcAnalysesCommand, BadKeyExitsWithTwoAndNamesIt) {
  const std::string mechsim = std::string(MECHSIM_BIN_DIR) + "/mechsim";
  ASSERT_TRUE(fs::exists(mechsim)) << mechsim;
  TempDir dir("bad-cli");
  for (const char* command : {"slide-modes", "motor-bode"}) {
    const std::string line = mechsim + " " + command + " " + cnc200_scene +
                             " --set design.slide_modes.ritz_shapez=4 > " + dir.file("out.txt") + " 2>&1";
    EXPECT_EQ(run(line), 2) << line;
    const std::string out = read_file(dir.file("out.txt"));
    EXPECT_NE(out.find("design.slide_modes.ritz_shapez"), std::string::npos) << out;
  }
}

}  // namespace
}  // namespace mechsim::tools::nc_analyses

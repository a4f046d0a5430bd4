// `mechsim cvt-map`: the JSON of the shipped scene against the CVT model evaluated directly
// (the map must be the model, point for point), its axes, the grid options, the refusals with
// their key paths, the clamping-force mode's gross slip, and one end-to-end run.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include "cvt_map.h"
#include "mechsim/config/scene.h"
#include "mechsim/models/cvt/cvt_model.h"
#include "plot.h"

namespace mechsim::tools::cvt_map {
namespace {

namespace fs = std::filesystem;
namespace cvt = models::cvt;
using nlohmann::json;

const std::string scene_file = std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/cvt_map.yaml";
constexpr double kRpm = std::numbers::pi / 30.0;

CvtMapResult map_of(const std::vector<std::string>& overrides = {}, const GridOptions& grid = {}) {
  return analyse_scene(config::load_scene(scene_file, overrides), overrides, grid);
}

std::vector<double> values(const json& axis) { return axis["values"].get<std::vector<double>>(); }

TEST(CvtMap, DefaultGridIsTheThesisGrid) {
  const json j = report_json(map_of());
  EXPECT_EQ(j["command"], "cvt-map");
  EXPECT_EQ(j["source"], "participants.cvt.params");
  // Axes in the thesis's units (mm, Nm, rpm), to rounding of the SI conversion.
  const std::vector<double> s = values(j["axes"]["s"]), t = values(j["axes"]["T_C"]), n = values(j["axes"]["n_C"]);
  ASSERT_EQ(s.size(), 5u);
  ASSERT_EQ(t.size(), 5u);
  ASSERT_EQ(n.size(), 5u);
  for (int k = 0; k < 5; ++k) {
    EXPECT_NEAR(s[k], 5.0 + 12.5 * k, 1e-9);
    EXPECT_NEAR(t[k], 20.0 + 25.0 * k, 1e-9);
    EXPECT_NEAR(n[k], 1000.0 * (k + 1), 1e-9);
  }
  const json& fk = j["fields"]["F_K"]["values"];
  ASSERT_EQ(fk.size(), 5u);
  ASSERT_EQ(fk[0].size(), 5u);
  ASSERT_EQ(fk[0][0].size(), 5u);
  for (const char* f : {"T_1", "F_K", "eta_PB", "eta_SYS", "sigma_link_disc", "sigma_link_ring", "sigma_link_link",
                        "sigma_support", "slip_margin", "flags"})
    EXPECT_TRUE(j["fields"].contains(f)) << f;
}

// Grid values are the model's own numbers: exact equality with a direct evaluation (same
// code, same inputs), at corners and in the middle of the grid.
TEST(CvtMap, GridValuesAreTheModel) {
  const CvtMapResult map = map_of();
  const json j = report_json(map);
  cvt::CvtModel model;  // the scene holds the thesis rig, i.e. the defaults
  struct P {
    int is, it, in;
  };
  for (const P& p : {P{2, 0, 0}, P{2, 4, 4}, P{0, 2, 1}, P{4, 3, 2}}) {
    cvt::CvtOperatingPoint op;
    op.s = map.s[p.is];
    op.torque = map.torque[p.it];
    op.omega_C = map.speed[p.in];
    const cvt::CvtResult r = model.evaluate(op);
    const json& f = j["fields"];
    EXPECT_EQ(f["F_K"]["values"][p.is][p.it][p.in].get<double>(), r.F_K);
    EXPECT_EQ(f["eta_SYS"]["values"][p.is][p.it][p.in].get<double>(), r.eta_SYS);
    EXPECT_EQ(f["T_1"]["values"][p.is][p.it][p.in].get<double>(), r.T_1);
    EXPECT_EQ(f["sigma_link_link"]["values"][p.is][p.it][p.in].get<double>(), r.sigma[2] / 1e6);
    EXPECT_EQ(f["slip_margin"]["values"][p.is][p.it][p.in].get<double>(), r.v_KD);
  }
  // The CC7 input point: s = 30 mm, T_C = 20 Nm, 1000 rpm has F_K = 3994 N and
  // T_1 − T_C = T_Lprim = 0.5613 Nm (spec §9 CC7, ±0.00005 Nm).
  EXPECT_EQ(j["fields"]["F_K"]["values"][2][0][0].get<double>(), 3994.0);
  EXPECT_NEAR(j["fields"]["T_1"]["values"][2][0][0].get<double>() - 20.0, 0.5613, 0.00005);
  // L0 deviation is reported: L0 underestimates F_K (8.15 vs 8.15 … 10.24 T/r).
  const json& dev = j["L0"]["deviation_from_L1"]["F_K_relative"];
  EXPECT_LT(dev[0].get<double>(), -0.15);
  EXPECT_LE(dev[1].get<double>(), 0.0);
}

TEST(CvtMap, FinerGridOnRequest) {
  GridOptions g;
  g.s_points = 2;
  g.speed_points = 9;
  const CvtMapResult r = map_of({"design.cvt_map.torque.points=3"}, g);
  EXPECT_EQ(r.s.size(), 2u);
  EXPECT_NEAR(r.s.back(), 55e-3, 1e-15);
  EXPECT_EQ(r.torque.size(), 3u);
  EXPECT_NEAR(r.torque[1], 70.0, 1e-12);
  EXPECT_EQ(r.speed.size(), 9u);
  EXPECT_NEAR(r.speed[1], 1500.0 * kRpm, 1e-9);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The shipped scene with its clamping line replaced, written to a temporary file.
std::string scene_with_clamping(const std::string& clamping) {
  std::string text = read_file(scene_file);
  const std::string line = "clamping: {mode: safety_factor, safety_factor: 1.0}";
  const std::size_t at = text.find(line);
  if (at == std::string::npos) throw std::runtime_error("clamping line not found in " + scene_file);
  text.replace(at, line.size(), clamping);
  const std::string path = (fs::temp_directory_path() / ("cvt-map-clamp-" + std::to_string(::getpid()) + ".yaml")).string();
  std::ofstream(path) << text;
  return path;
}

// Below the slip limit the clamping-force mode reports gross slip: null, never a number.
TEST(CvtMap, ClampingForceModeFlagsGrossSlip) {
  const std::string path = scene_with_clamping("clamping: {mode: force, force: 20 kN}");
  const json j = report_json(analyse_scene(config::load_scene(path), {}));
  fs::remove(path);
  // 20 kN carries T_C = 0.0415·0.12·20000/cos 12° = 101.8 Nm at v_KD = 1: 120 Nm slips.
  EXPECT_TRUE(j["fields"]["eta_PB"]["values"][2][4][0].is_null());
  EXPECT_NE(j["fields"]["flags"]["values"][2][4][0].get<std::string>().find("gross_slip"), std::string::npos);
  EXPECT_TRUE(j["fields"]["eta_PB"]["values"][2][3][0].is_number());  // 95 Nm is carried
}

std::string refusal(const std::vector<std::string>& overrides) {
  try {
    map_of(overrides);
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(CvtMap, RefusesBadInputWithTheKeyPath) {
  EXPECT_NE(refusal({"participants.cvt.params.frction=0.1"}).find("participants.cvt.params"), std::string::npos);
  EXPECT_NE(refusal({"participants.cvt.params.friction.disc=-0.1"}).find("participants.cvt.params.friction.disc"),
            std::string::npos);
  EXPECT_NE(refusal({"participants.cvt.params.neutral_radius=41.5 Nm"}).find("neutral_radius"), std::string::npos);
  EXPECT_NE(refusal({"participants.cvt.params.filling_degree=1.2"}).find("filling_degree"), std::string::npos);
  EXPECT_NE(refusal({"participants.cvt.params.clamping.force=1 kN"}).find("clamping.force"), std::string::npos);
  const std::string path = scene_with_clamping("clamping: {mode: force, force: -1 kN}");
  try {
    analyse_scene(config::load_scene(path), {});
    ADD_FAILURE() << "a negative clamping force was accepted";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("participants.cvt.params.clamping.force"), std::string::npos) << e.what();
  }
  fs::remove(path);
  EXPECT_NE(refusal({"design.cvt_map.ratio_setting.from=-5 mm"}).find("design.cvt_map.ratio_setting"),
            std::string::npos);
  EXPECT_NE(refusal({"design.cvt_map.speed.points=0"}).find("design.cvt_map.speed.points"), std::string::npos);
  EXPECT_NE(refusal({"design.cvt_map.torque.from=-20 Nm"}).find("design.cvt_map.torque"), std::string::npos);
  EXPECT_NE(refusal({"design.cvt_map.speed.to=5000 Nm"}).find("design.cvt_map.speed.to"), std::string::npos);
  EXPECT_EQ(refusal({"design.cvt_map.torque.points=2"}), "(accepted)");
}

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(CvtMapCommand, WritesJsonAndPlots) {
  const std::string mechsim = std::string(MECHSIM_BIN_DIR) + "/mechsim";
  ASSERT_TRUE(fs::exists(mechsim)) << mechsim;
  const fs::path dir = fs::temp_directory_path() / ("mechsim-cvt-map-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string out = (dir / "out.txt").string(), json_path = (dir / "map.json").string();
  const std::string command = mechsim + " cvt-map " + scene_file + " --json " + json_path + " --plots " +
                              (dir / "plots").string() + " --speed-points 3 > " + out + " 2>&1";
  ASSERT_EQ(run(command), 0) << command << "\n" << read_file(out);
  const json r = json::parse(read_file(json_path));
  EXPECT_EQ(r["axes"]["n_C"]["values"].size(), 3u);
  EXPECT_NE(read_file(out).find("s = 30 mm"), std::string::npos);
  const std::string bad = mechsim + " cvt-map " + scene_file + " --set participants.cvt.params.beltt=split > " + out + " 2>&1";
  EXPECT_EQ(run(bad), 2);
  EXPECT_NE(read_file(out).find("beltt"), std::string::npos);
  if (plot::gnuplot_available()) {
    for (const char* png : {"efficiency.png", "belt_efficiency.png", "clamping_force.png", "link_link_stress.png"})
      EXPECT_GT(fs::file_size(dir / "plots" / png), 0u) << png;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace mechsim::tools::cvt_map

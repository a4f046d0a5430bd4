// The two pieces of tools/bench-peer.sh that mechsim builds: the scene for libcosim
// (`mechsim bench --peer-system`: FMUs, OspSystemStructure.xml, the peer's coupling as
// --set overrides) and the models-alone floor (`mechsim bench --models-alone`).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>

#include <unistd.h>

#include "models_alone.h"
#include "peer_system.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/scene_plan.h"

namespace mechsim::bench {
namespace {

std::string shipped(const std::string& name) { return std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/" + name; }

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::filesystem::path fresh_dir(const std::string& stem) {
  const auto dir = std::filesystem::temp_directory_path() / ("mechsim-peer-test-" + std::to_string(::getpid())) / stem;
  std::filesystem::remove_all(dir);
  return dir;
}

// The exporter looks for its binary next to the running executable; a test runs elsewhere.
void use_build_fmu_binary() { ::setenv("MECHSIM_FMU_BINARY", MECHSIM_BIN_DIR "/mechsim_fmu.so", 1); }

TEST(PeerSystem, OneConnectionPerPortOfThePlanNamedAsTheFmusNameThem) {
  use_build_fmu_binary();
  const auto dir = fresh_dir("cam_press");
  std::ostringstream out;
  ASSERT_EQ(write_peer_system(shipped("cam_press.yaml"), {{}, dir.string()}, out), 0) << out.str();
  EXPECT_TRUE(std::filesystem::exists(dir / "cam.fmu"));
  EXPECT_TRUE(std::filesystem::exists(dir / "follower.fmu"));

  // As many VariableConnections as the plan has (topic field -> block input) pairs.
  const config::Scene scene = config::load_scene(shipped("cam_press.yaml"), {});
  const cosim::ScenePlan plan = cosim::ScenePlan::build(scene);
  std::size_t ports = 0;
  for (const auto& node : plan.nodes())
    for (const auto& edge : node.inputs) ports += edge.field_to_input.size();
  const std::string xml = read(dir / "OspSystemStructure.xml");
  const std::regex connection("<VariableConnection>");
  EXPECT_EQ(static_cast<std::size_t>(std::distance(std::sregex_iterator(xml.begin(), xml.end(), connection), std::sregex_iterator())),
            ports);
  EXPECT_NE(xml.find("<BaseStepSize>0.001</BaseStepSize>"), std::string::npos);
  EXPECT_NE(xml.find("<Algorithm>fixedStep</Algorithm>"), std::string::npos);
  // The follower reads the cam's acceleration and publishes its own: its input is the
  // exported `acceleration_in` (docs/fmi.md), the cam's output keeps its name.
  EXPECT_NE(xml.find("<Variable simulator=\"cam\" name=\"acceleration\"/>\n"
                     "      <Variable simulator=\"follower\" name=\"acceleration_in\"/>"),
            std::string::npos)
      << xml;
  // The cam -> follower edge is Gauss-Seidel; the peer couples it Jacobi. The follower ->
  // cam edge is Jacobi and held already.
  EXPECT_EQ(read(dir / "peer-coupling.sets"), "connections[0].order=jacobi\n");
}

TEST(PeerSystem, RefusesAnInterfaceJacobianCutWithTheReason) {
  use_build_fmu_binary();
  const auto dir = fresh_dir("nc_1ms");
  std::ostringstream out;
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(write_peer_system(shipped("nc_slide_loop_1ms.yaml"), {{}, dir.string()}, out), 2);
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("interface-Jacobian cut"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(dir / "OspSystemStructure.xml"));
}

TEST(ModelsAlone, StepsTheWholeGridAndWritesItsFigures) {
  const auto dir = fresh_dir("floor");
  std::filesystem::create_directories(dir);
  const std::string json_path = (dir / "floor.json").string();
  std::ostringstream out;
  ASSERT_EQ(run_models_alone(shipped("cam_press.yaml"), {{"time.end=0.5 s"}, json_path}, out), 0);
  const auto doc = nlohmann::json::parse(read(json_path));
  // Every step of the plan's grid: 500 uniform steps plus the boundaries the grid lands on
  // the follower's load steps before 0.5 s (the scene's scheduled events).
  const config::Scene scene = config::load_scene(shipped("cam_press.yaml"), {"time.end=0.5 s"});
  EXPECT_EQ(doc["steps"].get<std::uint64_t>(), cosim::ScenePlan::build(scene).grid()->steps());
  EXPECT_GE(doc["steps"].get<std::uint64_t>(), 500u);
  EXPECT_EQ(doc["participants"].get<int>(), 2);
  EXPECT_GT(doc["steps_per_s"].get<double>(), 0.0);
  EXPECT_NE(out.str().find("steps/s"), std::string::npos);
}

}  // namespace
}  // namespace mechsim::bench

// Placement (`participants.<p>.process: <group>`, docs/scenes.md): participants that share
// a process run as its threads, each still its own DDS participant on the same topics. On
// real processes over loopback (each run on a DDS domain of its own, as the launcher picks
// them): the node outputs are the bytes of the same scene with one process per node, on
// Cyclone DDS and on Fast DDS, for the whole scene in one process and for part of it.
#include <gtest/gtest.h>

#include <signal.h>

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mechsim/config/scene.h"
#include "run_fixture.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// --set entries that put `members` into process group `group`.
std::vector<std::string> group_of(const std::vector<std::string>& members, const std::string& group) {
  std::vector<std::string> out;
  for (const auto& m : members) out.insert(out.end(), {"--set", "participants." + m + ".process=" + group});
  return out;
}

std::vector<std::string> participants_of(const std::string& scene) {
  std::vector<std::string> names;
  for (const auto& p : config::load_scene(scene_path(scene)).participants) names.push_back(p.name);
  return names;
}

class Placement : public RunFolderTest {
 protected:
  // Launches the scene; returns its summary (null when it failed).
  json launch(const std::string& scene, const std::string& tag, std::vector<std::string> extra) {
    CommandResult r = run(launch_args(scene_path(scene), tag, extra), log(tag), 240);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return r.exit_code == 0 ? summary(tag) : json();
  }
  // One process per node, then every node in one process, on `vendor`: the same bytes;
  // the grouped run's nodes all write to the group's log (one process).
  void expect_one_process_gives_the_same_bytes(const std::string& scene, const std::string& vendor) {
    const std::vector<std::string> names = participants_of(scene);
    const json apart = launch(scene, vendor + "-apart", {"--dds", vendor, "--set", "processes=per_participant"});
    std::vector<std::string> together_args{"--dds", vendor};
    for (auto& a : group_of(names, "all")) together_args.push_back(a);
    const json together = launch(scene, vendor + "-together", together_args);
    ASSERT_FALSE(HasFailure());
    for (const auto& name : names) {
      EXPECT_EQ(together["nodes"][name]["vendor"], vendor) << name;
      EXPECT_EQ(together["nodes"][name]["exit"], "exit code 0") << name;
      EXPECT_EQ(fs::path(together["nodes"][name]["log"].get<std::string>()).filename(), "process-all.log") << name;
      EXPECT_FALSE(fs::exists(run_folder(vendor + "-together") / (name + ".log"))) << name << ": a process of its own";
    }
    EXPECT_EQ(apart["steps"], together["steps"]);
    expect_identical_node_outputs(run_folder(vendor + "-apart"), run_folder(vendor + "-together"), apart,
                                  "one process per node and one process for all (" + vendor + ")");
  }
};

TEST_F(Placement, CamPressInOneProcessIsByteIdenticalOnCyclone) { expect_one_process_gives_the_same_bytes("cam_press.yaml", "cyclone"); }
TEST_F(Placement, CamPressInOneProcessIsByteIdenticalOnFastDds) { expect_one_process_gives_the_same_bytes("cam_press.yaml", "fastdds"); }
TEST_F(Placement, NcSlideLoopInOneProcessIsByteIdenticalOnCyclone) {
  expect_one_process_gives_the_same_bytes("nc_slide_loop.yaml", "cyclone");
}
TEST_F(Placement, NcSlideLoopInOneProcessIsByteIdenticalOnFastDds) {
  expect_one_process_gives_the_same_bytes("nc_slide_loop.yaml", "fastdds");
}
TEST_F(Placement, PressLineInOneProcessIsByteIdenticalOnCyclone) { expect_one_process_gives_the_same_bytes("press_line.yaml", "cyclone"); }
TEST_F(Placement, PressLineInOneProcessIsByteIdenticalOnFastDds) { expect_one_process_gives_the_same_bytes("press_line.yaml", "fastdds"); }

// Part of a scene in a group, its members on two vendors (the mixed layout alternates them),
// next to a node process: the wire between vendors and processes sees no difference.
TEST_F(Placement, AMixedVendorGroupNextToANodeProcessIsByteIdentical) {
  const json apart = launch("nc_slide_loop.yaml", "apart", {"--dds", "cyclone"});
  std::vector<std::string> args{"--dds", "mixed"};
  for (auto& a : group_of({"servo", "tacho"}, "drive")) args.push_back(a);
  const json grouped = launch("nc_slide_loop.yaml", "grouped", args);
  ASSERT_FALSE(HasFailure());
  EXPECT_NE(grouped["nodes"]["servo"]["vendor"], grouped["nodes"]["tacho"]["vendor"]);
  EXPECT_EQ(fs::path(grouped["nodes"]["servo"]["log"].get<std::string>()).filename(), "process-drive.log");
  EXPECT_EQ(fs::path(grouped["nodes"]["slide"]["log"].get<std::string>()).filename(), "slide.log");
  expect_identical_node_outputs(run_folder("apart"), run_folder("grouped"), apart, "one process per node and the 'drive' group");
}

// `processes: N` (docs/scenes.md): the launcher packs the participants into N groups per
// vendor; with the mixed layout (cvt and follower on Fast DDS, cam on Cyclone) and N = 1 the
// two Fast DDS members share one DomainParticipant in one process beside the Cyclone one.
TEST_F(Placement, PackedProcessesPerVendorAreByteIdentical) {
  const json apart = launch("press_line.yaml", "per-participant", {"--dds", "mixed", "--set", "processes=per_participant"});
  const json packed = launch("press_line.yaml", "packed", {"--dds", "mixed", "--set", "processes=1"});
  ASSERT_FALSE(HasFailure());
  const auto log_of = [&](const char* node) { return fs::path(packed["nodes"][node]["log"].get<std::string>()).filename(); };
  EXPECT_EQ(packed["nodes"]["cvt"]["vendor"], "fastdds");
  EXPECT_EQ(log_of("cvt"), "process-auto_fastdds_1.log");
  EXPECT_EQ(log_of("follower"), "process-auto_fastdds_1.log");
  EXPECT_EQ(log_of("cam"), "process-auto_cyclone_1.log");
  EXPECT_EQ(apart["steps"], packed["steps"]);
  expect_identical_node_outputs(run_folder("per-participant"), run_folder("packed"), apart,
                                "a process per participant and processes: 1 (mixed vendors)");
}

// processes: auto, the default (docs/scenes.md): on one host a vendor's participants share
// one process, an FMU keeps its own, and the bytes are those of a process each.
TEST_F(Placement, TheDefaultPutsAVendorsParticipantsIntoOneProcessWithTheSameBytes) {
  const json apart = launch("press_line.yaml", "each", {"--set", "processes=per_participant"});
  const json automatic = launch("press_line.yaml", "auto", {});
  ASSERT_FALSE(HasFailure());
  for (const char* node : {"cvt", "cam", "follower"}) {
    EXPECT_EQ(fs::path(automatic["nodes"][node]["log"].get<std::string>()).filename(), "process-auto_cyclone_1.log") << node;
    EXPECT_EQ(fs::path(apart["nodes"][node]["log"].get<std::string>()).filename(), std::string(node) + ".log") << node;
  }
  expect_identical_node_outputs(run_folder("each"), run_folder("auto"), apart, "a process each and the default layout");
  // The mixed layout: the one Cyclone participant stays a node process, the two Fast DDS
  // ones share a process.
  const json mixed = launch("press_line.yaml", "mixed", {"--dds", "mixed"});
  ASSERT_FALSE(mixed.is_null());
  EXPECT_EQ(fs::path(mixed["nodes"]["cam"]["log"].get<std::string>()).filename(), "cam.log");
  EXPECT_EQ(fs::path(mixed["nodes"]["cvt"]["log"].get<std::string>()).filename(), "process-auto_fastdds_1.log");
  expect_identical_node_outputs(run_folder("each"), run_folder("mixed"), apart, "a process each and the default layout, mixed");
}

// A node of a group that fails ends the run like a node process that fails: the reason is
// the failing node's, and no process is left (the fixture checks).
TEST_F(Placement, ADivergingNodeInAGroupEndsTheRunCleanly) {
  std::vector<std::string> args{"--step", "200 us", "--set", "connections[0].reconstruction=hold", "--set",
                                "connections[1].reconstruction=hold", "--set", "connections[2].reconstruction=hold", "--set",
                                "connections[3].reconstruction=linear", "--set", "connections[4].reconstruction=linear"};
  for (auto& a : group_of({"servo", "tacho", "slide"}, "all")) args.push_back(a);
  CommandResult r = run(launch_args(scene_path("nc_slide_loop.yaml"), "diverged", args), log("diverged"), 240);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("diverged"), std::string::npos) << r.output;
  const json s = summary("diverged");
  EXPECT_EQ(s["status"], "failed");
  EXPECT_NE(s["failure"]["reason"].get<std::string>().find("diverged"), std::string::npos) << s["failure"].dump();
}

// A crash takes the whole group process: with restart: on_failure it is started again as a
// whole, every member resumes from the common checkpoint, and the run ends byte-identical to
// an undisturbed one, with a restart recorded for each member.
TEST_F(Placement, AKilledGroupProcessRestartsAsAWholeAndEndsByteIdentical) {
  const std::vector<std::string> members{"servo", "tacho", "slide"};
  std::vector<std::string> grouped{"--end", "3 s"};
  for (auto& a : group_of(members, "all")) grouped.push_back(a);
  const json plain = launch("nc_slide_loop_1ms.yaml", "plain", grouped);
  ASSERT_FALSE(plain.is_null());
  std::vector<std::string> args = grouped;
  // The slide holds the run while it writes its checkpoint of step 1000 (a third of the run:
  // many checkpoints behind it, most of the run ahead); the group's process is killed then,
  // however fast the machine is.
  args.insert(args.end(), {"--set", "faults.restart=on_failure", "--set", "faults.checkpoint_every=50", "--set",
                           "participants.slide.testing.checkpoint_pause_step=1000", "--set",
                           "participants.slide.testing.checkpoint_pause=3 s"});
  const pid_t launcher = spawn(launch_args(scene_path("nc_slide_loop_1ms.yaml"), "killed", args), log("killed"));
  StopOnExit stop{launcher};
  const fs::path run = wait_for_run_folder("killed");
  ASSERT_FALSE(run.empty()) << slurp(log("killed"));
  ASSERT_TRUE(wait_for_path(run / "checkpoints" / "slide.1000.ckpt.tmp", 120)) << slurp(log("killed"));
  pid_t group = -1;
  for (pid_t p : processes_mentioning((dir_ / "killed").string()))
    if (slurp("/proc/" + std::to_string(p) + "/cmdline").find("node_group") != std::string::npos) group = p;
  ASSERT_GT(group, 0) << "no node_group process";
  ::kill(group, SIGKILL);
  CommandResult r = wait_for(launcher, log("killed"), 180);
  stop.pid = -1;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json s = summary("killed");
  const json& restarts = s["restart"]["restarts"];
  ASSERT_EQ(restarts.size(), members.size()) << restarts.dump(1);
  for (const json& x : restarts) {
    EXPECT_EQ(x["exit"], "killed by signal 9 (Killed)");
    EXPECT_EQ(x["rollback_step"], 950) << "the slide's half-written checkpoint of step 1000 must not be used";
  }
  expect_identical_node_outputs(run_folder("plain"), run_folder("killed"), plain, "an undisturbed run and one with its group killed");
}

}  // namespace
}  // namespace mechsim::testing

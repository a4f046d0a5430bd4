// `processes: per_core | N` (tools/launch/process_packing.h, docs/scenes.md): which
// participants the launcher packs into which process group, on the shipped four-station line
// shaft (cvt, cam_1, follower_1, ..., cam_4, follower_4; it says processes: per_core).
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "mechsim/config/scene.h"
#include "process_packing.h"

namespace mechsim::launch {
namespace {

const std::string kLineShaft = MECHSIM_SOURCE_DIR "/config/scenes/line_shaft_4.yaml";

// participant -> group.
std::map<std::string, std::string> groups(const std::vector<PackedParticipant>& packed) {
  std::map<std::string, std::string> out;
  for (const auto& [participant, group] : packed) EXPECT_TRUE(out.emplace(participant, group).second) << participant << " twice";
  return out;
}

TEST(ProcessPacking, PerParticipantPacksNothing) {
  EXPECT_TRUE(pack_processes(config::load_scene(kLineShaft, {"processes=per_participant"}), 2).empty());
}

TEST(ProcessPacking, PerCoreKeepsNeighboursTogetherInOneGroupPerCore) {
  const auto g = groups(pack_processes(config::load_scene(kLineShaft, {"processes=per_core"}), 2));
  ASSERT_EQ(g.size(), 9u);
  // Nine participants on two cores: the first five, then the last four, in scene order.
  for (const char* p : {"cvt", "cam_1", "follower_1", "cam_2", "follower_2"}) EXPECT_EQ(g.at(p), "auto_cyclone_1") << p;
  for (const char* p : {"cam_3", "follower_3", "cam_4", "follower_4"}) EXPECT_EQ(g.at(p), "auto_cyclone_2") << p;
}

TEST(ProcessPacking, EachVendorGetsItsOwnGroupsAndNeverMoreGroupsThanMembers) {
  const auto g = groups(pack_processes(
      config::load_scene(kLineShaft, {"processes=4", "participants.cam_2.dds=fastdds", "participants.cam_3.dds=fastdds"}), 2));
  EXPECT_EQ(g.at("cam_2"), "auto_fastdds_1");
  EXPECT_EQ(g.at("cam_3"), "auto_fastdds_2");
  std::map<std::string, int> members;
  for (const auto& [p, group] : g) ++members[group];
  EXPECT_EQ(members.size(), 6u);  // four Cyclone groups of seven participants, two Fast DDS ones of one
  EXPECT_EQ(members["auto_cyclone_1"] + members["auto_cyclone_2"] + members["auto_cyclone_3"] + members["auto_cyclone_4"], 7);
}

TEST(ProcessPacking, ParticipantsThatChoseTheirProcessOrCannotJoinAGroupStayApart) {
  const auto g = groups(pack_processes(
      config::load_scene(kLineShaft, {"processes=per_core", "participants.cvt.process=drive", "participants.cam_4.realtime.priority=10",
                                      "participants.follower_4.restart=on_failure"}),
      1));
  EXPECT_FALSE(g.contains("cvt"));     // its own group, as written
  EXPECT_FALSE(g.contains("cam_4"));   // a realtime: of its own is a process's setting
  EXPECT_EQ(g.at("follower_4"), "auto_cyclone_2");  // restarts alone: not with members that do not restart
  for (const char* p : {"cam_1", "follower_1", "cam_2", "follower_2", "cam_3", "follower_3"}) EXPECT_EQ(g.at(p), "auto_cyclone_1") << p;
}

TEST(ProcessPacking, EachHostGetsItsOwnGroups) {
  const auto g = groups(pack_processes(
      config::load_scene(kLineShaft, {"processes=1", "dds.domain=5", "hosts.b.address=10.0.0.2", "participants.cam_3.host=b",
                                      "participants.follower_3.host=b", "participants.cam_4.host=b"}),
      2));
  for (const char* p : {"cam_3", "follower_3", "cam_4"}) EXPECT_EQ(g.at(p), "auto_b_cyclone_1") << p;
  for (const char* p : {"cvt", "cam_1", "follower_1", "cam_2", "follower_2", "follower_4"}) EXPECT_EQ(g.at(p), "auto_cyclone_1") << p;
}

// processes: auto (the default): on one host, unsecured, a vendor's participants share one
// process (a second group per core only past 8 of them); a vendor with one participant and
// an FMU keep a process of their own; several hosts: a process each.
TEST(ProcessPacking, TheDefaultPacksAVendorsParticipantsOfOneHostTogether) {
  const std::string cam_press = MECHSIM_SOURCE_DIR "/config/scenes/cam_press.yaml";
  const auto two = groups(pack_processes(config::load_scene(cam_press), 2));
  EXPECT_EQ(two.at("cam"), "auto_cyclone_1");
  EXPECT_EQ(two.at("follower"), "auto_cyclone_1");
  // Nine participants of one vendor: past 8, a second group (2 cores here).
  const auto nine = groups(pack_processes(config::load_scene(kLineShaft, {"processes=auto"}), 2));
  ASSERT_EQ(nine.size(), 9u);
  EXPECT_EQ(nine.at("cvt"), "auto_cyclone_1");
  EXPECT_EQ(nine.at("follower_4"), "auto_cyclone_2");
  // On one core: one group for all nine.
  for (const auto& [p, group] : groups(pack_processes(config::load_scene(kLineShaft, {"processes=auto"}), 1)))
    EXPECT_EQ(group, "auto_cyclone_1") << p;
  // A vendor with a single participant: a node process of its own.
  const auto mixed = groups(pack_processes(config::load_scene(cam_press, {"participants.cam.dds=fastdds"}), 2));
  EXPECT_TRUE(mixed.empty());
  // Across hosts, a process per participant.
  EXPECT_TRUE(pack_processes(config::load_scene(kLineShaft, {"processes=auto", "dds.domain=5", "hosts.b.address=10.0.0.2",
                                                             "participants.cam_3.host=b"}),
                             2)
                  .empty());
}

TEST(ProcessPacking, TheDefaultKeepsAnFmuInAProcessOfItsOwn) {
  const auto g = groups(pack_processes(config::load_scene(MECHSIM_SOURCE_DIR "/config/scenes/fmu_speed_lag.yaml"), 2));
  for (const auto& [p, group] : g) ADD_FAILURE() << p << " packed into " << group << ": an FMU participant";
}

}  // namespace
}  // namespace mechsim::launch

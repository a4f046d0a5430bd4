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

}  // namespace
}  // namespace mechsim::launch

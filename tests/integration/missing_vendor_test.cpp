// A build without one DDS vendor (MECHSIM_WITH_CYCLONEDDS=OFF or MECHSIM_WITH_FASTDDS=OFF)
// refuses a run that asks for the missing vendor, by name, before anything starts. Built
// and registered only in such a build: .ci/run builds it in build-no-CYCLONEDDS and
// build-no-FASTDDS and runs it there (a build with both vendors has nothing to refuse).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "mechsim/transport/backends.h"
#include "run_fixture.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;

class MissingVendor : public RunFolderTest {
 protected:
  // The vendor this build left out (CMake registers the suite only when there is one).
  static std::string missing() {
    const auto v = transport::available_vendors();
    for (const char* vendor : {"cyclone", "fastdds"})
      if (std::find(v.begin(), v.end(), vendor) == v.end()) return vendor;
    return "";
  }
  void expect_refused(const std::string& tag, const std::vector<std::string>& extra, const std::string& vendor) {
    const CommandResult r = run(launch_args(scene_path("cam_press.yaml"), tag, extra), log(tag), 60);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    // The key of the first participant that asks for it (`--dds` sets each participant's).
    EXPECT_NE(r.output.find("cam_press.yaml: participants.cam.dds: expected a DDS vendor compiled into this build, got '" +
                            vendor + "'"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(dir_ / tag)) << "a refused scene must not create a run folder";
    EXPECT_TRUE(processes_mentioning(dir_.string()).empty());
  }
};

TEST_F(MissingVendor, ALayoutOnTheMissingVendorIsRefused) {
  const std::string vendor = missing();
  ASSERT_FALSE(vendor.empty()) << "built with both vendors: this suite belongs to a build without one";
  expect_refused("all", {"--dds", vendor}, vendor);
}

// Mixed: participants alternate, the first (cam) on Fast DDS, the second on Cyclone.
TEST_F(MissingVendor, AMixedLayoutIsRefusedNamingTheParticipantOnTheMissingVendor) {
  const std::string vendor = missing();
  ASSERT_FALSE(vendor.empty()) << "built with both vendors: this suite belongs to a build without one";
  const CommandResult r = run(launch_args(scene_path("cam_press.yaml"), "mixed", {"--dds", "mixed"}), log("mixed"), 60);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const std::string participant = vendor == "fastdds" ? "cam" : "follower";
  EXPECT_NE(r.output.find("participants." + participant + ".dds: expected a DDS vendor compiled into this build, got '" +
                          vendor + "'"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "mixed")) << "a refused scene must not create a run folder";
}

// One participant moved to the missing vendor by the scene's own key.
TEST_F(MissingVendor, AParticipantKeyNamingTheMissingVendorIsRefused) {
  const std::string vendor = missing();
  ASSERT_FALSE(vendor.empty()) << "built with both vendors: this suite belongs to a build without one";
  const CommandResult r =
      run(launch_args(scene_path("cam_press.yaml"), "one", {"--set", "participants.follower.dds=" + vendor}), log("one"), 60);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("participants.follower.dds: expected a DDS vendor compiled into this build, got '" + vendor + "'"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "one")) << "a refused scene must not create a run folder";
}

}  // namespace
}  // namespace mechsim::testing

// `mechsim agent` on one machine's loopback (docs/hosts.md): it starts only mechsim node
// types, only into plain run-folder names, only for its own domain, and says why it
// refuses; a SIGTERM stops it. The launcher's side (AgentClient) talks to it over DDS as
// in a multi-host run; the multi-host runs themselves are in tests/hosts (root).
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "agent_client.h"
#include "mechsim/transport/domain_lock.h"
#include "mechsim/config/scene.h"
#include "mechsim/transport/backends.h"
#include "run_command.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

TEST(Agent, RefusesAnythingButAMechsimNodeOfItsDomain) {
  transport::DomainLock domain = transport::DomainLock::acquire();
  const fs::path dir = fs::temp_directory_path() / ("mechsim-agent-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  ::setenv("CYCLONEDDS_URI", "file://" MECHSIM_SOURCE_DIR "/config/dds/cyclonedds-loopback.xml", 1);
  ::setenv("FASTRTPS_DEFAULT_PROFILES_FILE", MECHSIM_SOURCE_DIR "/config/dds/fastdds-shm.xml", 1);
  const pid_t agent = spawn({std::string(MECHSIM_BIN_DIR) + "/mechsim", "agent", "--domain", std::to_string(domain.domain_id()),
                             "--work-dir", (dir / "work").string(), "--exit-after", "60"},
                            (dir / "agent.log").string());
  {
    auto participant = transport::create_participant(config::default_dds_vendor(), domain.domain_id());
    hostrun::AgentClient client(*participant, 42, (dir / "run").string());
    fs::create_directories(dir / "run");
    ASSERT_TRUE(client.wait_for_agents({"127.0.0.1"}, 20, [] { return false; }).empty()) << slurp((dir / "agent.log").string());
    const json good{{"type", "follower"}, {"scene_yaml", ""}, {"run_folder", "r"}, {"domain", domain.domain_id()},
                    {"address", "127.0.0.1"}, {"peers", {"127.0.0.1"}}};
    json shell = good, escape = good, other_domain = good;
    shell["type"] = "/bin/sh";
    escape["run_folder"] = "../outside";
    other_domain["domain"] = domain.domain_id() + 1;
    client.start("a", "127.0.0.1", shell.dump());
    client.start("b", "127.0.0.1", escape.dump());
    client.start("c", "127.0.0.1", other_domain.dump());
    std::map<std::string, std::string> refused;
    for (int i = 0; i < 500 && refused.size() < 3; ++i) {
      for (const auto& e : client.take_exits()) refused[e.node] = e.describe;
      participant->wait(std::chrono::milliseconds(10));
    }
    ASSERT_EQ(refused.size(), 3u) << slurp((dir / "agent.log").string());
    EXPECT_NE(refused["a"].find("'/bin/sh' is not a mechsim node type"), std::string::npos) << refused["a"];
    EXPECT_NE(refused["b"].find("run_folder must be a plain folder name"), std::string::npos) << refused["b"];
    EXPECT_NE(refused["c"].find("this agent serves " + std::to_string(domain.domain_id())), std::string::npos) << refused["c"];
    EXPECT_FALSE(fs::exists(dir / "outside"));
    EXPECT_TRUE(client.collect(10).empty());
  }
  ::kill(agent, SIGTERM);
  const CommandResult r = wait_for(agent, (dir / "agent.log").string(), 10);
  EXPECT_FALSE(r.timed_out);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("mechsim agent: stopped"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

// Two agents on one work folder would overwrite each other's DDS configuration and hand
// back (then remove) each other's node files: the second is refused, naming the folder and
// the agent holding it; once the first has stopped, the folder is free again.
TEST(Agent, ASecondAgentOnAWorkFolderInUseIsRefused) {
  transport::DomainLock domain = transport::DomainLock::acquire();
  const fs::path dir = fs::temp_directory_path() / ("mechsim-agent-lock-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  ::setenv("CYCLONEDDS_URI", "file://" MECHSIM_SOURCE_DIR "/config/dds/cyclonedds-loopback.xml", 1);
  const std::string mechsim = std::string(MECHSIM_BIN_DIR) + "/mechsim";
  const std::vector<std::string> argv{mechsim, "agent", "--domain", std::to_string(domain.domain_id()), "--work-dir",
                                      (dir / "work").string(), "--exit-after", "60"};
  const pid_t first = spawn(argv, (dir / "first.log").string());
  // The first holds the folder once it says it serves (the lock is taken before that line).
  for (int i = 0; i < 200 && slurp((dir / "first.log").string()).find("serving domain") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_NE(slurp((dir / "first.log").string()).find("serving domain"), std::string::npos) << slurp((dir / "first.log").string());
  const CommandResult second = run(argv, (dir / "second.log").string(), 30);
  EXPECT_EQ(second.exit_code, 1) << second.output;
  EXPECT_NE(second.output.find("work folder " + (dir / "work").string() + " is in use by another mechsim agent (pid " +
                               std::to_string(first) + ","),
            std::string::npos)
      << second.output;
  ::kill(first, SIGTERM);
  EXPECT_EQ(wait_for(first, (dir / "first.log").string(), 10).exit_code, 0);
  // Free again: a third agent takes it and serves.
  std::vector<std::string> third_argv = argv;
  third_argv.back() = "1";
  const CommandResult third = run(third_argv, (dir / "third.log").string(), 30);
  EXPECT_EQ(third.exit_code, 0) << third.output;
  EXPECT_NE(third.output.find("work folder " + (dir / "work").string() + ","), std::string::npos) << third.output;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace mechsim::testing

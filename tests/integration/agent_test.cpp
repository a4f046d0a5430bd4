// `mechsim agent` on one machine's loopback (docs/hosts.md): it starts only mechsim node
// types, only into plain run-folder names, only for its own domain, and says why it
// refuses; a SIGTERM stops it. The launcher's side (AgentClient) talks to it over DDS as the
// standing daemon, and over stdin/stdout as `mechsim agent --stdio` (the session an SSH
// link starts; here without ssh); the multi-host runs themselves are in tests/hosts (root).
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "agent_client.h"
#include "ssh_agent_link.h"
#include "mechsim/transport/domain_lock.h"
#include "mechsim/config/scene.h"
#include "mechsim/transport/backends.h"
#include "run_command.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Removes a test's folder while an agent session may still be removing its own work folder
// inside it (the session ends after the client): tolerates entries that vanish under it.
void remove_test_dir(const fs::path& dir) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::error_code ec;
    fs::remove_all(dir, ec);
    if (!ec && !fs::exists(dir)) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

// The requests a start must pass, on either transport: refused by the agent, each naming why.
void expect_refusals(hostrun::AgentClient& client, int domain, const fs::path& log) {
  const json good{{"type", "follower"}, {"scene_yaml", ""}, {"run_folder", "r"}, {"domain", domain},
                  {"address", "127.0.0.1"}, {"peers", {"127.0.0.1"}}};
  json shell = good, escape = good, other_domain = good;
  shell["type"] = "/bin/sh";
  escape["run_folder"] = "../outside";
  other_domain["domain"] = domain + 1;
  client.start("a", "127.0.0.1", shell.dump());
  client.start("b", "127.0.0.1", escape.dump());
  client.start("c", "127.0.0.1", other_domain.dump());
  client.start("d", "127.0.0.1", "not json");
  std::map<std::string, std::string> refused;
  for (int i = 0; i < 500 && refused.size() < 4; ++i) {
    for (const auto& e : client.take_exits()) refused[e.node] = e.describe;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_EQ(refused.size(), 4u) << slurp(log.string());
  EXPECT_NE(refused["a"].find("'/bin/sh' is not a mechsim node type"), std::string::npos) << refused["a"];
  EXPECT_NE(refused["b"].find("run_folder must be a plain folder name"), std::string::npos) << refused["b"];
  EXPECT_NE(refused["c"].find("this agent serves " + std::to_string(domain)), std::string::npos) << refused["c"];
  EXPECT_NE(refused["d"].find("not a JSON object"), std::string::npos) << refused["d"];
}

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
    hostrun::AgentClient client(hostrun::dds_agent_link(*participant), 42, (dir / "run").string());
    fs::create_directories(dir / "run");
    ASSERT_TRUE(client.wait_for_agents({"127.0.0.1"}, 20, [] { return false; }).empty()) << slurp((dir / "agent.log").string());
    expect_refusals(client, domain.domain_id(), dir / "agent.log");
    EXPECT_FALSE(fs::exists(dir / "outside"));
    EXPECT_TRUE(client.collect(10).empty());
  }
  ::kill(agent, SIGTERM);
  const CommandResult r = wait_for(agent, (dir / "agent.log").string(), 10);
  EXPECT_FALSE(r.timed_out);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("mechsim agent: stopped"), std::string::npos) << r.output;
  remove_test_dir(dir);
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
  remove_test_dir(dir);
}

// The session's agent (what `ssh HOST mechsim agent --stdio` runs): the same refusals as the
// daemon, since both hand requests to one AgentService; it ends with its session (stdin
// closed), saying so, and removes its work folder.
TEST(StdioAgent, RefusesLikeTheDaemonAndEndsWithItsSession) {
  const fs::path dir = fs::temp_directory_path() / ("mechsim-stdio-agent-test-" + std::to_string(::getpid()));
  remove_test_dir(dir);
  fs::create_directories(dir / "run");
  const int domain = 9;  // no DDS participant is made: any domain
  {
    std::vector<hostrun::SshSession> sessions{{"127.0.0.1",
                                               {std::string(MECHSIM_BIN_DIR) + "/mechsim", "agent", "--stdio", "--domain",
                                                std::to_string(domain), "--work-dir", (dir / "work").string()},
                                               (dir / "session.log").string()}};
    hostrun::AgentClient client(hostrun::ssh_agent_link(sessions), 42, (dir / "run").string());
    ASSERT_TRUE(client.wait_for_agents({"127.0.0.1"}, 20, [] { return false; }).empty()) << slurp((dir / "session.log").string());
    EXPECT_NE(client.agents().at("127.0.0.1").find("\"vendor\":\"ssh\""), std::string::npos) << client.agents().at("127.0.0.1");
    expect_refusals(client, domain, dir / "session.log");
    EXPECT_FALSE(fs::exists(dir / "outside"));
    EXPECT_TRUE(client.collect(10).empty());
  }
  // The client and its link are gone: the session's end stopped the agent, which said why.
  const std::string log = slurp((dir / "session.log").string());
  EXPECT_NE(log.find("serving the session of "), std::string::npos) << log;
  EXPECT_NE(log.find("session over: the launcher closed the session"), std::string::npos) << log;
  EXPECT_NE(log.find("refused node 'a' of run 42 from the session of "), std::string::npos) << log;
  remove_test_dir(dir);
}

// A host's bounds (docs/hosts.md, "Bounds"): with --max-processes 1 a second node is refused
// while the first runs, and with --max-file-bytes a start request whose scene is larger.
TEST(StdioAgent, RefusesWhatWouldExceedTheHostsBounds) {
  const fs::path dir = fs::temp_directory_path() / ("mechsim-stdio-bounds-test-" + std::to_string(::getpid()));
  remove_test_dir(dir);
  fs::create_directories(dir / "run");
  const int domain = 9;
  const std::string scene = slurp(MECHSIM_SOURCE_DIR "/config/scenes/cam_press.yaml");
  std::vector<hostrun::SshSession> sessions{{"127.0.0.1",
                                             {std::string(MECHSIM_BIN_DIR) + "/mechsim", "agent", "--stdio", "--domain",
                                              std::to_string(domain), "--work-dir", (dir / "work").string(), "--max-processes", "1",
                                              "--max-file-bytes", std::to_string(scene.size() + 1000)},
                                             (dir / "session.log").string()}};
  hostrun::AgentClient client(hostrun::ssh_agent_link(sessions), 43, (dir / "run").string());
  ASSERT_TRUE(client.wait_for_agents({"127.0.0.1"}, 20, [] { return false; }).empty()) << slurp((dir / "session.log").string());
  const json start{{"type", "follower"}, {"scene_yaml", scene}, {"run_folder", "r"}, {"domain", domain},
                   {"address", "127.0.0.1"}, {"peers", {"127.0.0.1"}}};
  json cam = start, big = start;
  cam["type"] = "cam_shaft";
  big["scene_yaml"] = scene + std::string(2000, '#');
  client.start("follower", "127.0.0.1", start.dump());
  client.start("cam", "127.0.0.1", cam.dump());
  client.start("big", "127.0.0.1", big.dump());
  std::map<std::string, std::string> refused;
  for (int i = 0; i < 500 && refused.size() < 2; ++i) {
    for (const auto& e : client.take_exits()) refused[e.node] = e.describe;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(refused.count("follower"), 0u) << refused["follower"];
  EXPECT_NE(refused["cam"].find("this host runs 1 node processes, its --max-processes 1"), std::string::npos) << refused["cam"];
  EXPECT_NE(refused["big"].find("exceeds this host's --max-file-bytes " + std::to_string(scene.size() + 1000)), std::string::npos)
      << refused["big"];
  EXPECT_TRUE(client.collect(20).empty());
  remove_test_dir(dir);
}

// Bytes that are not agent frames (or a frame over the limit) end the session at once, with a
// log line naming the sender; nothing is started.
TEST(StdioAgent, RefusesASessionThatSendsSomethingElse) {
  const std::string mechsim = std::string(MECHSIM_BIN_DIR) + "/mechsim";
  const fs::path dir = fs::temp_directory_path() / ("mechsim-stdio-junk-test-" + std::to_string(::getpid()));
  remove_test_dir(dir);
  fs::create_directories(dir);
  const CommandResult junk = run({"/bin/sh", "-c", "printf 'GET / HTTP/1.1\\r\\n\\r\\n' | " + mechsim + " agent --stdio --domain 9 --work-dir " +
                                                       (dir / "w1").string()},
                                 (dir / "junk.log").string(), 30);
  EXPECT_EQ(junk.exit_code, 0) << junk.output;
  EXPECT_NE(junk.output.find("refused the session of "), std::string::npos) << junk.output;
  EXPECT_NE(junk.output.find("bytes that are not a mechsim agent frame"), std::string::npos) << junk.output;
  // "MSA1" and a body length of 0x7fffffff: refused on the header, before any body is read.
  const CommandResult big = run({"/bin/sh", "-c", "printf 'MSA1\\377\\377\\377\\177' | " + mechsim + " agent --stdio --domain 9 --work-dir " +
                                                      (dir / "w2").string()},
                                (dir / "big.log").string(), 30);
  EXPECT_NE(big.output.find("a frame of 2147483647 bytes, over the limit of 4194304 bytes"), std::string::npos) << big.output;
  remove_test_dir(dir);
}

// The standing daemon authenticates nobody: on a non-loopback address it refuses to serve,
// naming the option that accepts the risk.
TEST(Agent, ADaemonOnANetworkAddressIsRefusedWithoutTheOptionThatAcceptsTheRisk) {
  const fs::path dir = fs::temp_directory_path() / ("mechsim-agent-open-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const CommandResult r = run({std::string(MECHSIM_BIN_DIR) + "/mechsim", "agent", "--domain", "9", "--address", "10.99.88.77",
                               "--work-dir", (dir / "w").string(), "--exit-after", "1"},
                              (dir / "open.log").string(), 30);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("refused to serve --address 10.99.88.77: the DDS agent authenticates nobody"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("add --allow-unauthenticated"), std::string::npos) << r.output;
  // With it, the next check speaks: the address is not this machine's.
  const CommandResult allowed = run({std::string(MECHSIM_BIN_DIR) + "/mechsim", "agent", "--domain", "9", "--address", "10.99.88.77",
                                     "--allow-unauthenticated", "--work-dir", (dir / "w").string(), "--exit-after", "1"},
                                    (dir / "allowed.log").string(), 30);
  EXPECT_EQ(allowed.exit_code, 1) << allowed.output;
  EXPECT_NE(allowed.output.find("--address 10.99.88.77 is not an address of this host"), std::string::npos) << allowed.output;
  remove_test_dir(dir);
}

}  // namespace
}  // namespace mechsim::testing

// The node process's command line (node_command_line.h): what the launcher and the agent
// build is what the node executables parse back, and a bad one is refused by CLI11.
#include "mechsim/cosim/node_command_line.h"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace mechsim::cosim {
namespace {

// Parses `args` as a node executable does; CLI11's exit code on a parse error, else 0.
int parse(NodeCommandLine& into, NodeProcessShape shape, const std::vector<std::string>& args) {
  CLI::App app{"test"};
  into.add_options(app, shape);
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes the last first
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    return e.get_exit_code();
  }
  return 0;
}

TEST(NodeCommandLine, ANodeProcessParsesBackWhatTheLauncherBuilds) {
  NodeCommandLine built{.scene = "runs/a/scene.yaml", .nodes = {"cam"}, .run_id = 18446744073709551615u, .domain = 232,
                        .run_dir = "runs/a", .control_writer = "0123456789abcdef01234567:89abcdef", .replays = {"t.csv"}};
  built.resume_step = 40;
  built.generation = 3;
  const std::vector<std::string> args = built.to_arguments();
  EXPECT_EQ(args, (std::vector<std::string>{"--scene", "runs/a/scene.yaml", "--node", "cam", "--run-id", "18446744073709551615",
                                            "--domain", "232", "--run-dir", "runs/a", "--control-writer",
                                            "0123456789abcdef01234567:89abcdef", "--replay", "t.csv", "--resume", "40",
                                            "--generation", "3"}));
  NodeCommandLine parsed;
  ASSERT_EQ(parse(parsed, NodeProcessShape::node, args), 0);
  EXPECT_EQ(parsed.scene, built.scene);
  EXPECT_EQ(parsed.nodes, built.nodes);
  EXPECT_EQ(parsed.run_id, built.run_id);
  EXPECT_EQ(parsed.domain, built.domain);
  EXPECT_EQ(parsed.run_dir, built.run_dir);
  EXPECT_EQ(parsed.control_writer, built.control_writer);
  EXPECT_EQ(parsed.replays, built.replays);
  EXPECT_EQ(parsed.resume_step, built.resume_step);
  EXPECT_EQ(parsed.generation, built.generation);
}

TEST(NodeCommandLine, AFirstStartOmitsWhatItDoesNotUse) {
  const NodeCommandLine built{.scene = "s.yaml", .nodes = {"cam"}, .run_id = 7, .domain = 0};
  EXPECT_EQ(built.to_arguments(),
            (std::vector<std::string>{"--scene", "s.yaml", "--node", "cam", "--run-id", "7", "--domain", "0"}));
  NodeCommandLine parsed;
  ASSERT_EQ(parse(parsed, NodeProcessShape::node, built.to_arguments()), 0);
  EXPECT_FALSE(parsed.resume_step.has_value());
  EXPECT_EQ(parsed.generation, 0);
  EXPECT_TRUE(parsed.run_dir.empty());
  EXPECT_TRUE(parsed.replays.empty());
}

TEST(NodeCommandLine, AGroupRepeatsNodeAndReplay) {
  const NodeCommandLine built{.scene = "s.yaml", .nodes = {"amp", "tacho"}, .run_id = 1, .domain = 5,
                              .replays = {"amp=a.csv", "tacho=t.csv"}};
  NodeCommandLine parsed;
  ASSERT_EQ(parse(parsed, NodeProcessShape::group, built.to_arguments()), 0);
  EXPECT_EQ(parsed.nodes, built.nodes);
  EXPECT_EQ(parsed.replays, built.replays);
}

TEST(NodeCommandLine, ABadCommandLineIsRefusedWithCli11sExitCode) {
  const std::vector<std::string> base{"--scene", "s.yaml", "--node", "cam", "--run-id", "1"};
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> args = base;
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };
  NodeCommandLine c;
  EXPECT_EQ(parse(c, NodeProcessShape::node, base), static_cast<int>(CLI::ExitCodes::RequiredError));  // no --domain
  NodeCommandLine d;
  EXPECT_EQ(parse(d, NodeProcessShape::node, with({"--domain", "233"})), static_cast<int>(CLI::ExitCodes::ValidationError));
  NodeCommandLine g;
  EXPECT_EQ(parse(g, NodeProcessShape::node, with({"--domain", "1", "--generation", "2"})),
            static_cast<int>(CLI::ExitCodes::RequiresError));
  NodeCommandLine two;  // a node process runs one node; a group takes several
  EXPECT_EQ(parse(two, NodeProcessShape::node, with({"--domain", "1", "--node", "follower"})),
            static_cast<int>(CLI::ExitCodes::ArgumentMismatch));
  NodeCommandLine group;
  EXPECT_EQ(parse(group, NodeProcessShape::group, with({"--domain", "1", "--node", "follower"})), 0);
}

}  // namespace
}  // namespace mechsim::cosim

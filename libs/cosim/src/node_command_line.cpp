#include "mechsim/cosim/node_command_line.h"

#include <CLI/CLI.hpp>

namespace mechsim::cosim {

std::vector<std::string> NodeCommandLine::to_arguments() const {
  std::vector<std::string> args{"--scene", scene};
  for (const std::string& node : nodes) args.insert(args.end(), {"--node", node});
  args.insert(args.end(), {"--run-id", std::to_string(run_id), "--domain", std::to_string(domain)});
  if (!run_dir.empty()) args.insert(args.end(), {"--run-dir", run_dir});
  // The node takes commands from this writer only (docs/faults.md).
  if (!control_writer.empty()) args.insert(args.end(), {"--control-writer", control_writer});
  for (const std::string& replay : replays) args.insert(args.end(), {"--replay", replay});
  if (resume_step) args.insert(args.end(), {"--resume", std::to_string(*resume_step), "--generation", std::to_string(generation)});
  return args;
}

void NodeCommandLine::add_options(CLI::App& app, NodeProcessShape shape) {
  const bool group = shape == NodeProcessShape::group;
  app.add_option("--scene", scene, "scene file (the run folder's resolved scene.yaml)")->required();
  if (group)
    app.add_option("--node", nodes, "a participant of the group (repeated)")->required();
  else
    app.add_option_function<std::string>("--node", [this](const std::string& node) { nodes = {node}; },
                                         "participant instance name in the scene")
        ->required();
  app.add_option("--run-id", run_id, "run id the samples carry")->required();
  app.add_option("--domain", domain, "DDS domain id")->required()->check(CLI::Range(0, 232));
  app.add_option("--run-dir", run_dir, group ? "folder for the nodes' output logs (omit: none)" : "folder for this node's output log (omit: none)");
  app.add_option("--control-writer", control_writer,
                 "GUID of the launcher's mechsim/control writer: a command of this run from any other writer fails the run");
  if (group)
    app.add_option("--replay", replays, "NODE=TABLE: the node publishes this table (written by `mechsim launch --replay`)");
  else
    app.add_option_function<std::string>(
        "--replay", [this](const std::string& table) { replays = {table}; },
        "publish the values of this table (written by `mechsim launch --replay`) instead of computing them");
  auto* resume = app.add_option_function<std::uint64_t>(
      "--resume", [this](std::uint64_t step) { resume_step = step; },
      group ? "restart after a crash: every node resumes from its checkpoint of this step (docs/faults.md)"
            : "restart after a crash: resume from this node's checkpoint of this step in the run folder, once the "
              "launcher sends resume (docs/faults.md)");
  app.add_option("--generation", generation,
                 group ? "the rollback generation the resumed nodes belong to" : "the rollback generation a resumed node belongs to")
      ->needs(resume);
}

}  // namespace mechsim::cosim

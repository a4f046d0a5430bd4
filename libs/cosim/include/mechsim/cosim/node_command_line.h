// The command line of a node process, in one place for both of its ends: the hosts that
// start node processes build it (tools/launch for this machine, tools/agent on another
// host) and the node executables parse it (nodes/common). A node process runs one node,
//   <type> --scene RUN_DIR/scene.yaml --node NAME --run-id ID --domain D [--run-dir DIR]
//          [--control-writer GUID] [--replay TABLE] [--resume STEP --generation G]
// and a process group (`participants.<p>.process`, docs/scenes.md) runs several,
//   node_group --scene ... --node A --node B ... [--replay A=TABLE ...] ...
// It lives in cosim, below both tools and nodes (docs/architecture.md), beside the exit
// codes of the same processes (node_host.h); a bad command line exits as CLI11 does.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace mechsim::cosim {

// One node per process, or the members of a process group.
enum class NodeProcessShape { node, group };

// Default member initializers: the hosts build it with designated initializers.
struct NodeCommandLine {
  std::string scene{};               // --scene: the run folder's resolved scene.yaml
  std::vector<std::string> nodes{};  // --node: one for a node process, each member of a group
  std::uint64_t run_id = 0;          // --run-id: the run id the samples carry
  int domain = 0;                    // --domain: the DDS domain id
  std::string run_dir{};             // --run-dir: the folder of the output logs (empty: none)
  std::string control_writer{};      // --control-writer: GUID of the launcher's control writer
  // --replay: a node process's recorded table; a group's NODE=TABLE per replayed member.
  std::vector<std::string> replays{};
  std::optional<std::uint64_t> resume_step{};  // --resume: restart from this step's checkpoint
  std::int32_t generation = 0;                 // --generation: the rollback a resumed node belongs to

  // The arguments after the executable, in the order above (--generation only with --resume).
  std::vector<std::string> to_arguments() const;

  // Registers the options on `app`, which parses into this object (so it must outlive the
  // parse): the required ones, the domain's range, --generation only with --resume. A node
  // process takes one --node and one --replay, a group repeats them.
  void add_options(CLI::App& app, NodeProcessShape shape);
};

}  // namespace mechsim::cosim

// The record a node leaves in the run folder when it has taken its last step:
// <run folder>/<node>.end, one line "step N t T". The launcher tells by it a node that
// finished from one whose process ended early with exit code 0 (an FMU that calls exit(0)
// in its step): the exit code cannot tell them apart, and the node's final "done" status
// travels best effort. It is also where the summary reads the step a node reached.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace mechsim::cosim {

struct NodeEnd {
  std::uint64_t step = 0;
  double t = 0.0;
};

std::string node_end_record_path(const std::string& run_dir, const std::string& node);
// Written by a node after its last step (atomically: a rename). Throws on a write error.
void write_node_end_record(const std::string& run_dir, const std::string& node, const NodeEnd& end);
// Removed by a node when it starts (a restarted node has not finished yet).
void remove_node_end_record(const std::string& run_dir, const std::string& node);
// nullopt when the node has not written it (or it is unreadable).
std::optional<NodeEnd> read_node_end_record(const std::string& run_dir, const std::string& node);

}  // namespace mechsim::cosim

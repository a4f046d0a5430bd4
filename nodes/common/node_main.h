// The shared main of every node process. The launcher starts a node as
//   <type> --scene RUN_DIR/scene.yaml --node NAME --run-id ID --domain D [--run-dir DIR]
// (the whole command line: mechsim/cosim/node_command_line.h) with CYCLONEDDS_URI pointing
// at the loopback configuration.
#pragma once

namespace mechsim::nodes {

// Returns the process exit code: 0 done, 1 failed, 2 bad arguments or scene, 3 stopped.
int node_main(const char* node_type, int argc, char** argv);

// The process of a process group (`participants.<p>.process`, docs/scenes.md):
//   node_group --scene RUN_DIR/scene.yaml --node A --node B ... --run-id ID --domain D
// steps its nodes on one executor thread, each its own DDS participant. The exit code is the first
// failing node's, else 0.
int node_group_main(int argc, char** argv);

}  // namespace mechsim::nodes

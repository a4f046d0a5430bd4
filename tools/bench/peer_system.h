// `mechsim bench SCENE --peer-system DIR` (issue 42 item 5): the scene for another
// co-simulation master, libcosim (tools/bench-peer.sh, docs/performance.md "Against a peer:
// libcosim"): every participant exported as an FMI 2 co-simulation FMU into DIR/<name>.fmu
// (the code of `mechsim fmu export`), and DIR/OspSystemStructure.xml with one simulator per
// participant and one VariableConnection per connected port, from the scene's plan (topic
// field -> reader's block input, named as the exported FMUs name them), and
// DIR/peer-coupling.sets: the `--set` overrides (one a line) that couple the scene as the
// peer does, for a mechsim run of the same coupling.
//
// What the peer cannot take is refused with the reason, not approximated: an
// interface-Jacobian cut (its predictions are no FMI variables), a participant played by
// an FMU, an adaptive macro step. What it takes differently is said: OSP's fixedStep
// algorithm couples every edge Jacobi with the sample held, where the scene may ask for
// Gauss-Seidel or a reconstruction, so the step is the same work but not the same numbers.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace mechsim::bench {

struct PeerSystemOptions {
  std::vector<std::string> set_overrides;
  std::string dir;  // created if missing
};

// Returns the exit code (0 written, 1 an export failed, 2 a scene the peer cannot take:
// the message names the participant or connection and why).
int write_peer_system(const std::string& scene_path, const PeerSystemOptions& options, std::ostream& out);

}  // namespace mechsim::bench

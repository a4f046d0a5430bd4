// Node process `fmu`: a participant of type fmu, an FMU with ports of its own (docs/fmi.md);
// see nodes/common/node_main.h.
#include "node_main.h"

int main(int argc, char** argv) { return mechsim::nodes::node_main("fmu", argc, argv); }

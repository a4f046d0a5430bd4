// Process `node_group`: several participants of a scene stepped by one thread of one process; see
// nodes/common/node_main.h.
#include "node_main.h"

int main(int argc, char** argv) { return mechsim::nodes::node_group_main(argc, argv); }

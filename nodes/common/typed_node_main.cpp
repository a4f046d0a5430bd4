// The node process of one native node type (nodes/CMakeLists.txt compiles this file once
// per type with MECHSIM_NODE_TYPE set): see node_main.h.
#include "node_main.h"

#ifndef MECHSIM_NODE_TYPE
#error "MECHSIM_NODE_TYPE names the node type (nodes/CMakeLists.txt)"
#endif

int main(int argc, char** argv) { return mechsim::nodes::node_main(MECHSIM_NODE_TYPE, argc, argv); }

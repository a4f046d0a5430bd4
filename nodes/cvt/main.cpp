// Node process `cvt`: see nodes/common/node_main.h.
#include "node_main.h"

int main(int argc, char** argv) { return mechsim::nodes::node_main("cvt", argc, argv); }

// Node process `servo_amplifier`: see nodes/common/node_main.h.
#include "node_main.h"

int main(int argc, char** argv) { return mechsim::nodes::node_main("servo_amplifier", argc, argv); }

/* The first-order lag of lag/lag.c with a shaft speed as input and output (rad/s): the
 * same law, so that a native participant's speed can drive it (tests/integration/fmu_participant_test.cpp). */
#include "../lag/lag.c"

// `mechsim launch --replay NODE=FILE`: the recorded topic of NODE, taken out of an MCAP
// recording into the table the node process replays (replay_block.h). Everything that can
// be wrong with the recording is found here, before any process starts.
#pragma once

#include <string>

#include "mechsim/cosim/scene_plan.h"
#include "mechsim/cosim/step_grid.h"

namespace mechsim::launch {

struct ReplayRequest {
  std::string node;  // participant instance name
  std::string file;  // MCAP recording
};

// "amp=run.mcap" -> {amp, run.mcap}; throws std::invalid_argument without '='.
ReplayRequest parse_replay_request(const std::string& text);

// Reads `node`'s topic from the recording and writes it as an output log (columns "t" and
// the topic's fields, one row per step 0..N) to `table_path`. Throws std::runtime_error
// naming the file when the recording is unreadable, lacks the topic, mixes several runs on
// it, skips a step or ends before the scene does. A truncated recording is read as far as
// it goes (recover it first with `mechsim record --recover` for the rest).
void write_replay_table(const std::string& recording, const cosim::PlannedNode& node, const cosim::StepGrid& grid,
                        const std::string& table_path);

}  // namespace mechsim::launch

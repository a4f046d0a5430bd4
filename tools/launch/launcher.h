// `mechsim launch`: one distributed run of a scene. Validates the scene, gives the run a
// folder, a run id and a free DDS domain, starts one process per participant, waits until
// every node is ready end to end, sends start, shows progress, watches for nodes that die
// or hang, and at the end compares the compared signals with the monolithic reference and
// writes the summary. Every process is stopped on every path out.
#pragma once

#include <string>
#include <vector>

namespace mechsim::launch {

struct LaunchOptions {
  std::string scene_path;
  std::vector<std::string> overrides;  // "dotted.key=value"
  std::string json_path;               // summary copy for scripts ("" = none)
  std::string runs_dir = "runs";       // run folders go to <runs_dir>/<scene>-<run id>/
  bool progress = true;                // progress line on a terminal
  bool plots = true;
  double ready_timeout_s = 30.0;       // from process start to all nodes ready
  std::string dds_layout;              // "" (the scene's vendors), "cyclone", "fastdds" or "mixed"
  // "NODE=FILE": the participant publishes what an MCAP recording holds for its topic
  // instead of computing it (docs/recording.md, replay_input.h).
  std::vector<std::string> replays;
  // "[ADDRESS:]PORT": serve the run live while it goes (tools/live, docs/live.md); "" none.
  std::string live;
  double live_rate_hz = 60.0;  // messages per second per channel and client, at most
};

// The scene overrides that put the launcher and every participant on one DDS vendor
// ("cyclone", "fastdds"), or alternate them ("mixed": the launcher on cyclone, the
// participants fastdds, cyclone, fastdds, ... in scene order). Throws std::invalid_argument
// for another layout.
std::vector<std::string> dds_layout_overrides(const std::vector<std::string>& participants, const std::string& layout);

// Returns the process exit code: 0 ok, 1 run failed, 2 bad scene, 130 interrupted.
int launch(const LaunchOptions& options);

}  // namespace mechsim::launch

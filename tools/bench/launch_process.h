// `mechsim launch` as a process of its own, its summary handed back as data: the bench's DDS
// spot checks run a point the way a user runs a scene and set it against the in-process run.
// A process, not a call of launch::launch(): that entry point returns only an exit code
// (the summary goes to a file) and takes over its process for the run (signal handlers, the
// DDS environment, stdout), so calling it here would need the launcher restructured first.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace mechsim::bench {

struct LaunchedRun {
  int exit_code = -1;                     // of `mechsim launch`; -1 when it did not exit normally
  double process_time_s = 0.0;            // from its start to its exit
  std::optional<nlohmann::json> summary;  // its summary JSON; none when it wrote none
  std::string log_path;                   // its stdout and stderr
};

// Runs `exe launch scene_file --set o ... --json dir/summary.json --runs-dir dir --no-plot
// --no-progress` (the run folder inside dir, its output in dir/launch.log; dir is created)
// and waits for it.
LaunchedRun run_mechsim_launch(const std::string& exe, const std::string& scene_file,
                               const std::vector<std::string>& overrides, const std::string& dir);

// The `mechsim` executable of this process (/proc/self/exe; the file's path even when it
// was rebuilt while this process runs).
std::string this_executable();

}  // namespace mechsim::bench

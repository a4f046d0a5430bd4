// `mechsim bench SCENE --stability` (issue 6 item 4): per connection and scheme, the largest
// stable macro step by bisection, next to a linear analysis of the macro-step map.
// Declaration only: the implementation (stability.cpp) belongs to the stability work; the
// `bench` command (tools/mechsim/cmd_bench.cpp) calls it when the flag is given.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace mechsim::bench {

struct StabilityOptions {
  std::string json_path;
  std::string plots_dir;
  std::vector<std::string> set_overrides;
  bool quick = false;
};

// Returns the process exit code (0 done, 1 failed, 2 bad scene or options).
int run_stability_bench(const std::string& scene_path, const StabilityOptions&, std::ostream& out);

}  // namespace mechsim::bench

// The summary of one run (summary.json: what ran where, how each node ended, the restarts,
// the solver figures, the events) and the report on the console.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hosts.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/cosim/supervisor.h"

namespace mechsim::launch {

// The run id as the run folder and the summary write it (16 hex digits).
std::string hex_id(std::uint64_t id);

// What the summary of a run is made of.
struct RunFacts {
  const config::Scene& scene;
  const cosim::ScenePlan& plan;
  std::uint64_t run_id;
  const std::string& run_dir;
  int domain;
  const hostrun::HostLayout& hosts;
  const std::map<std::string, std::string>* agents;  // the agents' hello texts (multi-host runs)
  const std::vector<std::string>& hand_back_problems;
  const cosim::Supervisor& supervisor;
  std::function<std::string(const std::string& node)> log_of;  // the log file of a node's process
};

nlohmann::json summarise(const RunFacts& run, const cosim::SupervisedRun& out);
// One line per node with its integrator statistics, and the stiffness hints.
void print_solver_health(const nlohmann::json& nodes);
// The console report of a finished run; returns the launcher's exit code.
int print_run_report(nlohmann::json& summary, const config::Scene& scene, std::uint64_t run_id, const std::string& run_dir,
                     const cosim::SupervisedRun& out);

}  // namespace mechsim::launch

#include "mechsim/cosim/inproc_run.h"

#include <algorithm>
#include <atomic>
#include <memory>

#include "mechsim/cosim/scene_plan.h"
#include "mechsim/cosim/supervisor.h"
#include "mechsim/cosim/thread_host.h"
#include "mechsim/transport/backends.h"

namespace mechsim::cosim {

namespace {

// In-process domains are private to this process: a counter keeps concurrent runs (tests,
// a bench) apart.
int next_domain() {
  static std::atomic<int> counter{0};
  return 1'000'000 + counter.fetch_add(1);
}

}  // namespace

InprocRunResult run_inproc(const config::Scene& scene, const InprocRunOptions& options) {
  const int domain = next_domain();
  std::vector<std::string> names;
  for (const auto& p : scene.participants) names.push_back(p.name);
  // One plan per node, like one per node process (blocks hold run state); built here, so
  // that a scene the plan refuses throws before any thread starts.
  std::map<std::string, std::unique_ptr<ScenePlan>> plans;
  for (const auto& name : names) plans[name] = std::make_unique<ScenePlan>(ScenePlan::build(scene));

  auto launcher = transport::create_participant("inproc", domain);
  auto control = launcher->create_control_writer();
  auto status = launcher->create_status_reader();

  NodeRunOptions node_options;
  node_options.run_dir = options.run_dir;
  node_options.run_id = options.run_id;
  ThreadNodeHost threads(
      names,
      [&](const std::string& node) {
        return ThreadNodeHost::Parts{std::move(plans.at(node)), transport::create_participant("inproc", domain)};
      },
      node_options);

  SupervisorOptions so;
  so.run_id = options.run_id;
  so.run_dir = options.run_dir;
  so.ready_timeout_s = options.ready_timeout_s;
  so.hang_timeout_s = scene.hang_timeout;
  so.fault_timings = config::fault_timings(scene);
  // In process the nodes step flat out: lock-step whatever the scene's mode.
  so.start = transport::ControlMessage{options.run_id, transport::ControlCommand::start, scene.time.end, scene.time.step,
                                       transport::RunMode::lockstep, scene.rtf, 0, 0, 0, {}};
  SupervisorHooks hooks;
  if (options.progress)
    hooks.progress = [&](const NodeWatches& watches, double, bool final_line) {
      if (final_line) return;
      std::uint64_t step = UINT64_MAX;
      for (const auto& [name, w] : watches) step = std::min<std::uint64_t>(step, w.seen ? w.last.header.step : 0);
      options.progress(step);
    };
  Supervisor supervisor(*launcher, *control, *status, {&threads}, so, hooks);
  const SupervisedRun run = supervisor.run();
  threads.stop_all(0);
  supervisor.take_final_statuses();

  InprocRunResult result;
  result.ok = run.ok;
  result.failed_node = run.failed_node;
  result.reason = run.reason;
  result.diverged = run.diverged;
  result.failed_step = run.failed_step;
  result.wall_time_s = run.wall_time_s;
  for (const auto& name : names) result.nodes.push_back({name, threads.exit_code(name), supervisor.watches().at(name).last});
  return result;
}

}  // namespace mechsim::cosim

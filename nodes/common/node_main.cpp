#include "node_main.h"
#include "node_setup.h"

#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <sys/prctl.h>

#include <CLI/CLI.hpp>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/fmu_unpacking.h"
#include "mechsim/cosim/node_command_line.h"
#include "mechsim/cosim/node_runner.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/process_realtime.h"
#include "mechsim/cosim/replay_block.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/transport/backends.h"

namespace mechsim::nodes {

namespace {
std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop.store(true); }
}  // namespace

std::unique_ptr<cosim::ScenePlan> node_plan(const config::Scene& scene, const std::string& node_name, const std::string& replay) {
  auto plan = std::make_unique<cosim::ScenePlan>(cosim::ScenePlan::build(scene));
  if (!replay.empty()) {
    cosim::PlannedNode& node = plan->node(node_name);
    cosim::replace_with_replay(node, cosim::recorded_topic_from_log(cosim::read_output_log(replay), *node.type->publishes, replay),
                               plan->grid());
  }
  return plan;
}

void apply_realtime(const config::Scene& scene, const config::ParticipantSpec& spec, const std::string& run_dir,
                    const std::vector<std::string>& names) {
  // Real-time mode only (a lock-step run of FIFO nodes flat out would starve the rest of
  // the machine), and before the DDS participant exists, so that the vendor's threads
  // inherit the policy.
  const bool paced = scene.mode == config::RunMode::realtime;
  const cosim::AppliedRealtime applied = paced ? cosim::apply_process_realtime(spec.process_realtime) : cosim::AppliedRealtime{};
  if (paced && spec.process_realtime.any()) {
    std::printf("process: %s\n", applied.describe().c_str());
    if (!run_dir.empty())
      for (const auto& name : names) applied.write_json(run_dir + "/" + name + ".process.json");
  }
}

void apply_testing_seams(const config::ParticipantSpec& spec, cosim::NodeRunOptions& options) {
  options.lose_first_writes_after_resume = spec.lose_writes_after_resume;
  options.lose_write_of_step = spec.lose_write_of_step;
  options.checkpoint_pause_step = spec.checkpoint_pause_step;
  options.checkpoint_pause_s = spec.checkpoint_pause;
  options.lose_failed_status = spec.lose_failed_status;
}

cosim::NodeRunOptions run_options(const cosim::NodeCommandLine& command_line) {
  cosim::NodeRunOptions options;
  options.run_dir = command_line.run_dir;
  options.run_id = command_line.run_id;
  options.domain = command_line.domain;
  options.control_writer = command_line.control_writer;
  options.resume_step = command_line.resume_step;
  options.generation = command_line.generation;
  return options;
}

void stop_on_signals() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

const std::atomic<bool>& stop_signalled() { return g_stop; }

int node_main(const char* node_type, int argc, char** argv) {
  // Logs go to a file in the run folder: keep them line by line so a crash loses nothing.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  // Never outlive the launcher (it may be killed without a chance to stop us).
  prctl(PR_SET_PDEATHSIG, SIGTERM);

  CLI::App app{std::string("mechsim node '") + node_type +
               "': one participant of a scene. Normally started by `mechsim launch`."};
  cosim::NodeCommandLine command_line;
  command_line.add_options(app, cosim::NodeProcessShape::node);
  CLI11_PARSE(app, argc, argv);
  const std::string& scene_path = command_line.scene;
  const std::string& node_name = command_line.nodes.front();

  stop_on_signals();
  try {
    // An FMU unpacks in the run folder, where the launcher removes it whatever becomes of us.
    if (!command_line.run_dir.empty()) cosim::unpack_fmus_in_run_folder(command_line.run_dir);
    config::Scene scene = config::load_scene(scene_path);
    const auto* spec = scene.find_participant(node_name);
    if (!spec) {
      std::cerr << node_type << ": no participant '" << node_name << "' in " << scene_path << "\n";
      return cosim::node_exit_code::bad_input;
    }
    if (spec->type != node_type) {
      std::cerr << node_type << ": participant '" << node_name << "' is a " << spec->type << ", not a " << node_type << "\n";
      return cosim::node_exit_code::bad_input;
    }
    std::unique_ptr<cosim::ScenePlan> plan =
        node_plan(scene, node_name, command_line.replays.empty() ? std::string() : command_line.replays.front());
    apply_realtime(scene, *spec, command_line.run_dir, {node_name});
    auto participant = transport::create_participant(spec->vendor, command_line.domain);
    cosim::NodeRunOptions options = run_options(command_line);
    options.stop_requested = &g_stop;
    apply_testing_seams(*spec, options);
    return cosim::run_node(*plan, node_name, *participant, options);
  } catch (const config::ConfigError& e) {
    std::cerr << e.what() << "\n";
    return cosim::node_exit_code::bad_input;
  } catch (const std::exception& e) {
    std::cerr << node_type << " '" << node_name << "': " << e.what() << "\n";
    return cosim::node_exit_code::failed;
  }
}

}  // namespace mechsim::nodes

#include <sys/prctl.h>

#include <csignal>
#include <cstdio>
#include <iostream>
#include <map>

#include <CLI/CLI.hpp>

#include "mechsim/cosim/fmu_unpacking.h"
#include "mechsim/cosim/thread_host.h"
#include "mechsim/transport/backends.h"
#include "node_main.h"
#include "node_setup.h"

namespace mechsim::nodes {

int node_group_main(int argc, char** argv) {
  // Logs go to a file in the run folder: keep them line by line so a crash loses nothing.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  // Never outlive the launcher (it may be killed without a chance to stop us).
  prctl(PR_SET_PDEATHSIG, SIGTERM);

  CLI::App app{"mechsim process group: several participants of a scene stepped by one thread of one process, each with its own "
               "endpoints (Fast DDS members share one DomainParticipant; participants.<p>.process, docs/scenes.md). "
               "Normally started by `mechsim launch`."};
  cosim::NodeCommandLine command_line;
  command_line.add_options(app, cosim::NodeProcessShape::group);
  CLI11_PARSE(app, argc, argv);
  const std::string& scene_path = command_line.scene;
  const std::vector<std::string>& node_names = command_line.nodes;
  const int domain = command_line.domain;

  stop_on_signals();
  try {
    // An FMU unpacks in the run folder, where the launcher removes it whatever becomes of us.
    if (!command_line.run_dir.empty()) cosim::unpack_fmus_in_run_folder(command_line.run_dir);
    const config::Scene scene = config::load_scene(scene_path);
    std::map<std::string, std::string> replay_of;
    for (const auto& r : command_line.replays) {
      const auto eq = r.find('=');
      if (eq == std::string::npos) {
        std::cerr << "node group: --replay expects NODE=TABLE, got '" << r << "'\n";
        return cosim::node_exit_code::bad_input;
      }
      replay_of[r.substr(0, eq)] = r.substr(eq + 1);
    }
    const config::ParticipantSpec* first = nullptr;
    for (const auto& name : node_names) {
      const auto* spec = scene.find_participant(name);
      if (!spec) {
        std::cerr << "node group: no participant '" << name << "' in " << scene_path << "\n";
        return cosim::node_exit_code::bad_input;
      }
      if (spec->process.empty() || (first && spec->process != first->process)) {
        std::cerr << "node group: participant '" << name << "' is not in process group '" << (first ? first->process : spec->process)
                  << "' of " << scene_path << "\n";
        return cosim::node_exit_code::bad_input;
      }
      if (!first) first = spec;
    }
    apply_realtime(scene, *first, command_line.run_dir, node_names);
    cosim::NodeRunOptions options = run_options(command_line);
    cosim::ThreadNodeHost threads(
        node_names,
        [&](const std::string& node) {
          const config::ParticipantSpec& spec = *scene.find_participant(node);
          cosim::NodeRunOptions own = options;  // each member's own test seams
          apply_testing_seams(spec, own);
          return cosim::ThreadNodeHost::Parts{node_plan(scene, node, replay_of.count(node) ? replay_of[node] : ""),
                                              transport::create_group_member_participant(spec.vendor, domain), std::move(own)};
        },
        options);
    threads.start_all();
    // The process ends with its nodes; the first node that fails stops the others (its
    // exit code is the process's), as a node process that fails ends its node.
    int code = cosim::node_exit_code::done;
    for (std::size_t running = node_names.size(); running > 0;) {
      for (const cosim::NodeExit& e : threads.poll()) {
        --running;
        if (const int c = threads.exit_code(e.node); c != cosim::node_exit_code::done && code == cosim::node_exit_code::done) {
          code = c;
          threads.request_stop();
        }
      }
      if (stop_signalled()) threads.request_stop();
      threads.wait_for_exit(std::chrono::milliseconds(100));
    }
    threads.stop_all(0);
    return code;
  } catch (const config::ConfigError& e) {
    std::cerr << e.what() << "\n";
    return cosim::node_exit_code::bad_input;
  } catch (const std::exception& e) {
    std::cerr << "node group: " << e.what() << "\n";
    return cosim::node_exit_code::failed;
  }
}

}  // namespace mechsim::nodes

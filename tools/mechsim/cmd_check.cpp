#include <cstdio>
#include <map>
#include <numbers>
#include <string>

#include "commands.h"
#include "mechsim/config/scene.h"
#include "fmu_probe.h"
#include "mechsim/cosim/fmu_probe.h"
#include "mechsim/cosim/process_realtime.h"
#include "mechsim/cosim/scene_plan.h"
#include "process_packing.h"
#include "run_security.h"

namespace mechsim::tools {

void add_check_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("check", "Validate a scene without running it (exit 2 when it is refused)");
  auto args = std::make_shared<SceneArgs>();
  add_scene_args(cmd, *args);
  cmd->callback([args, &exit_code] {
    try {
      config::Scene scene = config::load_scene(args->scene, args->overrides());
      cosim::defer_fmu_instantiation();  // an FMU's code runs in a child of ours, below
      cosim::ScenePlan plan = cosim::ScenePlan::build(scene);
      if (const std::string why = probe_fmus_in_children(args->scene, args->overrides(), plan, ""); !why.empty()) {
        std::fprintf(stderr, "mechsim check: %s\n", why.c_str());
        exit_code = 2;
        return;
      }
      // A secured scene: what the launcher would refuse before starting anything (the
      // folder's files, one vendor, a domain the governance covers; docs/security.md).
      if (const auto problems = launch::security_problems(scene); !problems.empty()) {
        for (const auto& why : problems) std::fprintf(stderr, "mechsim check: %s\n", why.c_str());
        exit_code = 2;
        return;
      }
      if (const auto& a = scene.time.adaptive)
        std::printf("%s: scene '%s' is valid: an adaptive step of %g .. %g s (tolerance %g), %zu participants\n",
                    scene.file.c_str(), scene.name.c_str(), a->min, a->max, a->tolerance, plan.nodes().size());
      else
        std::printf("%s: scene '%s' is valid: %ld steps of %g s, %zu participants\n", scene.file.c_str(),
                    scene.name.c_str(), static_cast<long>(plan.grid()->steps()), scene.time.step, plan.nodes().size());
      for (const auto& e : plan.scheduled_events())
        std::printf("  a step lands on t = %.9g s (scheduled by %s)\n", e.t, e.participant.c_str());
      // Angles whose time is known only during the run (the shaft's speed varies).
      for (const auto& node : plan.nodes())
        for (const auto& events : node.run_time_angle_events) {
          std::string angles;
          for (double a : events.angles) {
            char buf[32];
            std::snprintf(buf, sizeof buf, "%s%g", angles.empty() ? "" : ", ", a * 180.0 / std::numbers::pi);
            angles += buf;
          }
          if (events.own_outputs)
            std::printf("  steps land where %s's angle reaches %s deg (its law's joints; predicted during the run, "
                        "its speed varies)\n", node.name().c_str(), angles.c_str());
          else
            std::printf("  steps land where %s's input angle reaches %s deg (its loads' ends; predicted during the run, "
                        "the shaft's speed varies)\n", node.name().c_str(), angles.c_str());
        }
      // A sampled block's ticks bound an adaptive step (landed on, not events).
      if (scene.time.adaptive)
        for (const auto& node : plan.nodes())
          if (node.block->sample_time() > 0)
            std::printf("  steps land on %s's sample instants, every %g s (no step is longer)\n", node.name().c_str(),
                        node.block->sample_time());
      // Where each participant runs: its own process, a group it names, or one the launcher
      // packs it into (`processes:`, docs/scenes.md).
      std::map<std::string, std::string> group_of;
      for (const auto& p : scene.participants)
        if (!p.process.empty()) group_of[p.name] = p.process;
      const int cores = launch::usable_cores();
      for (const auto& [participant, group] : launch::pack_processes(scene, cores))
        group_of[participant] = group + " (processes: " +
                                (scene.processes.kind == config::ProcessLayout::Kind::automatic ? std::string("auto")
                                 : scene.processes.count > 0 ? std::to_string(scene.processes.count) + " per vendor"
                                                             : "per_core, " + std::to_string(cores) + " cores here") +
                                ")";
      for (const auto& node : plan.nodes()) {
        std::printf("  %-12s %-12s publishes %-24s (%d states, %s)\n", node.name().c_str(), node.type->name.c_str(),
                    node.topic.c_str(), node.block->num_states(), node.spec->vendor.c_str());
        for (const auto& e : node.inputs)
          std::printf("  %12s <- %s (%s, %s)\n", "", e.topic.c_str(),
                      e.order == config::EdgeOrder::jacobi ? "jacobi" : "gauss_seidel",
                      e.reconstruction == config::Reconstruction::hold     ? "hold"
                      : e.reconstruction == config::Reconstruction::linear ? "linear"
                                                                           : "quadratic");
        // Node solver tolerances; under an adaptive step they follow its tolerance unless written.
        if (const auto& a = scene.time.adaptive; node.block->num_states() > 0 && a) {
          const config::SolverSpec& solver = node.spec->solver;
          const char* why = !solver.rtol_written ? " (from the adaptive tolerance: rtol = min(1e-6, tolerance x 1e-4))"
                            : solver.rtol > a->tolerance * config::kAdaptiveSolverRtolPerTolerance
                                ? " (written; looser than tolerance x 1e-4: this node's own error may exceed the "
                                  "coupling tolerance, docs/accuracy.md)"
                                : "";
          std::printf("  %12s solver %s, rtol %g, atol %g%s\n", "", solver.method.c_str(), solver.rtol, solver.atol, why);
        }
        if (!node.spec->host.empty()) {
          const config::HostSpec* host = scene.find_host(node.spec->host);
          std::printf("  %12s on host %s (%s; started by its mechsim agent unless the launcher runs there)\n", "",
                      host->name.c_str(), host->address.c_str());
        }
        if (auto g = group_of.find(node.name()); g != group_of.end())
          std::printf("  %12s in process group %s\n", "", g->second.c_str());
        if (node.cut)
          std::printf("  %12s <> %s (interface_jacobian, %d levels)\n", "", node.cut->partner_topic.c_str(), node.cut->levels);
        // Real-time process settings (applied in realtime mode only), and whether this user may.
        if (const auto& rt = node.spec->process_realtime; rt.any() && scene.mode == config::RunMode::realtime) {
          std::string cpus;
          for (int c : rt.cpus) cpus += (cpus.empty() ? "" : ",") + std::to_string(c);
          const std::string refusal = cosim::realtime_refusal(rt, cosim::current_process_rights());
          std::printf("  %12s realtime: %s, memory %s, cpus %s%s\n", "",
                      rt.priority > 0 ? ("SCHED_FIFO " + std::to_string(rt.priority)).c_str() : "SCHED_OTHER",
                      rt.lock_memory ? "locked" : "not locked", cpus.empty() ? "any" : cpus.c_str(),
                      refusal.empty() ? "" : ("  (refused for this user: " + refusal + ")").c_str());
        }
      }
      exit_code = 0;
    } catch (const config::ConfigError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      exit_code = 2;
    }
  });
}

}  // namespace mechsim::tools

#include "run_summary.h"

#include <cstdio>
#include <fstream>
#include <map>

#include "assessment_json.h"
#include "json_io.h"
#include "mechsim/cosim/composer.h"
#include "mechsim/cosim/node_end_record.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/step_grid.h"
#include "provenance.h"
#include "realtime_report.h"
#include "run_report.h"
#include "solver_health.h"

namespace mechsim::launch {

using nlohmann::json;

std::string hex_id(std::uint64_t id) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(id));
  return buf;
}

namespace {

// The solver figures of one node from its last status.
NodeSolverFigures solver_figures(const config::ParticipantSpec& spec, const transport::StatusMessage& last, long macro_steps,
                                 double macro_step) {
  NodeSolverFigures f;
  f.method = spec.solver.method;
  f.steps = last.solver_steps;
  f.rhs_evals = last.rhs_evals;
  f.error_test_failures = last.error_test_failures;
  f.nonlinear_failures = last.nonlinear_failures;
  f.roots_found = last.roots_found;
  f.last_step = last.last_step_size;
  f.last_order = last.last_order;
  f.macro_steps = macro_steps;
  f.macro_step = macro_step;
  return f;
}

// Where a node ran, how it ended, its solver statistics and health, its log.
json node_summary(const RunFacts& run, const std::string& name) {
  const auto& w = run.supervisor.watches().at(name);
  const auto* spec = run.scene.find_participant(name);
  const cosim::NodeHost& host = run.supervisor.host_of(name);
  json n = {{"type", spec->type},
            {"vendor", spec->vendor},
            {"host", !host.remote(name) ? (run.hosts.launcher_host.empty() ? "local" : run.hosts.launcher_host) : spec->host},
            {"exit", host.describe_exit(name)},
            // Where the node got to (its end record, else its output log), not the last status heard.
            {"last_step", run.supervisor.reached_step(name)},
            {"reached_end", cosim::read_node_end_record(run.run_dir, name).has_value()},
            {"solver",
             {{"steps", w.last.solver_steps},
              {"rhs_evals", w.last.rhs_evals},
              {"error_test_failures", w.last.error_test_failures},
              {"nonlinear_failures", w.last.nonlinear_failures},
              {"roots_found", w.last.roots_found},
              {"last_step_s", w.last.last_step_size},
              {"last_order", w.last.last_order}}},
            {"log", run.log_of(name)}};
  // Integrator health (solver_health.h): steps per macro step and the stiffness hint.
  const NodeSolverFigures health = solver_figures(*spec, w.last, w.seen ? static_cast<long>(w.last.header.step) : 0, run.scene.time.step);
  n["solver"]["method"] = health.method;
  n["solver"]["steps_per_macro_step"] = steps_per_macro_step(health);
  if (auto hint = stiffness_hint(health)) n["solver"]["stiffness_hint"] = *hint;
  return n;
}

// The restarts with rollback of the run (docs/faults.md) and their timings.
json restart_summary(const RunFacts& run) {
  json restarts = json::array();
  for (const auto& r : run.supervisor.restarts())
    restarts.push_back({{"node", r.node}, {"exit", r.exit}, {"last_step", r.last_step}, {"rollback_step", r.rollback_step},
                        {"generation", r.generation}, {"detected_s", r.detected_s}, {"resumed_s", r.resumed_s},
                        {"stepping_s", r.stepping_s},
                        {"kill_to_resume_s", r.resumed_s >= 0 ? r.resumed_s - r.detected_s : -1.0},
                        {"kill_to_stepping_s", r.stepping_s >= 0 ? r.stepping_s - r.detected_s : -1.0}});
  return {{"checkpoint_every", run.scene.faults.checkpoint_every}, {"restart_limit", run.scene.faults.restart_limit},
          {"restarts", restarts}};
}

}  // namespace

void print_solver_health(const json& nodes) {
  for (const auto& [name, n] : nodes.items()) {
    const json& s = n["solver"];
    if (s.value("steps", 0LL) == 0) continue;  // a node without states (or no status seen)
    std::printf("  solver %-10s %s: %lld steps (%.1f per macro step), %lld error-test / %lld convergence failures, %lld roots, last step %.3g s, order %lld\n",
                name.c_str(), s.value("method", std::string("?")).c_str(), s.value("steps", 0LL),
                s.value("steps_per_macro_step", 0.0), s.value("error_test_failures", 0LL), s.value("nonlinear_failures", 0LL),
                s.value("roots_found", 0LL), s.value("last_step_s", 0.0), s.value("last_order", 0LL));
  }
  for (const auto& [name, n] : nodes.items())
    if (n["solver"].contains("stiffness_hint"))
      std::printf("  hint: node '%s': %s\n", name.c_str(), n["solver"]["stiffness_hint"].get<std::string>().c_str());
}

json summarise(const RunFacts& run, const cosim::SupervisedRun& out) {
  json s;
  s["schema_version"] = tools::schema_version;
  s["provenance"] = tools::provenance(run.scene.file);
  s["scene"] = run.scene.name;
  s["scene_file"] = run.scene.file;
  s["run_id"] = hex_id(run.run_id);
  s["run_dir"] = run.run_dir;
  s["domain_id"] = run.domain;
  s["dds_vendor"] = run.scene.vendor;  // the launcher's own participant
  if (!run.scene.security_dir.empty()) {
    s["dds_security"] = run.scene.security_dir;
    s["dds_protection"] = run.scene.security_protection;
  }
  s["mode"] = config::to_string(run.scene.mode);
  s["redundant_samples"] = run.scene.faults.redundant();
  if (run.scene.checkpointing()) s["restart"] = restart_summary(run);
  s["status"] = out.ok ? "ok" : "failed";
  // A failed run stopped before its end: what it wrote covers part of the run only.
  s["complete"] = out.ok;
  s["macro_step_s"] = run.scene.time.step;
  s["simulated_time_s"] = run.scene.time.end - run.scene.time.start;
  // An adaptive run's steps are those its nodes logged (the launcher's own grid never grows).
  std::uint64_t steps = run.plan.grid()->steps();
  if (run.plan.grid()->is_adaptive()) {
    std::vector<double> instants;
    try {
      instants = cosim::run_instants(run.plan, run.run_dir);
    } catch (const std::exception&) {
      // a node that died before its log had a header: no instants
    }
    steps = instants.empty() ? 0 : instants.size() - 1;
    s["adaptive_step"] = adaptive_step_summary(*run.scene.time.adaptive, instants);
  }
  s["steps"] = steps;
  if (!run.plan.scheduled_events().empty()) {  // where the grid lands a boundary (docs/accuracy.md)
    nlohmann::json events = nlohmann::json::array();
    for (const auto& e : run.plan.scheduled_events()) events.push_back({{"participant", e.participant}, {"t_s", e.t}});
    s["scheduled_events"] = events;
  }
  s["wall_time_s"] = out.wall_time_s;
  s["steps_per_second"] = out.wall_time_s > 0 ? static_cast<double>(steps) / out.wall_time_s : 0.0;
  s["real_time_factor"] = out.wall_time_s > 0 ? (run.scene.time.end - run.scene.time.start) / out.wall_time_s : 0.0;
  if (!out.ok)
    s["failure"] = {{"node", out.failed_node}, {"last_step", out.failed_step}, {"reason", out.reason}};
  json nodes = json::object();
  for (const auto& node : run.plan.nodes()) nodes[node.name()] = node_summary(run, node.name());
  s["nodes"] = nodes;
  if (run.hosts.multi_host) {
    json agents = json::object();
    if (run.agents)
      for (const auto& [address, hello] : *run.agents) agents[address] = json::parse(hello, nullptr, false);
    s["hosts"] = {{"launcher_host", run.hosts.launcher_host}, {"launcher_address", run.hosts.launcher_address},
                  {"addresses", run.hosts.address}, {"agents", agents}, {"hand_back_problems", run.hand_back_problems}};
  }
  // Events the nodes reported (lift-off, landing, ...), from <node>.events.jsonl.
  json events = json::array();
  for (const auto& node : run.plan.nodes()) {
    std::ifstream in(run.run_dir + "/" + node.name() + ".events.jsonl");
    for (std::string line; std::getline(in, line);) {
      json e = json::parse(line, nullptr, false);
      if (e.is_discarded()) continue;
      e["node"] = node.name();
      events.push_back(e);
    }
  }
  s["events"] = events;
  std::vector<std::string> node_names;
  for (const auto& node : run.plan.nodes()) node_names.push_back(node.name());
  if (run.scene.mode == config::RunMode::realtime)
    s["realtime"] = realtime_summary(run.scene, *run.plan.grid(), node_names, run.run_dir, run.supervisor.warnings());
  s["process_realtime"] = process_settings_summary(node_names, run.run_dir);
  return s;
}

int print_run_report(json& summary, const config::Scene& scene, std::uint64_t run_id, const std::string& run_dir,
                     const cosim::SupervisedRun& out) {
  if (out.ok) {
    char of_length[160];
    if (const json* a = summary.contains("adaptive_step") ? &summary["adaptive_step"] : nullptr; a && (*a)["shortest_s"].is_number())
      std::snprintf(of_length, sizeof of_length, "adaptive steps of %g .. %g s (tolerance %g)", (*a)["shortest_s"].get<double>(),
                    (*a)["longest_s"].get<double>(), (*a)["tolerance"].get<double>());
    else
      std::snprintf(of_length, sizeof of_length, "steps of %g s", scene.time.step);
    std::printf("run %s of '%s': %llu %s in %.3f s wall: %.0f steps/s, real-time factor %.2f\n",
                hex_id(run_id).c_str(), scene.name.c_str(), static_cast<unsigned long long>(summary["steps"].get<std::uint64_t>()),
                of_length, out.wall_time_s, summary["steps_per_second"].get<double>(), summary["real_time_factor"].get<double>());
    if (summary.contains("reference") && summary["reference"].contains("compared_with") && !summary["signals"].empty())
      std::printf("  compared with %s\n", summary["reference"]["compared_with"].get<std::string>().c_str());
    for (auto& [name, e] : summary["signals"].items()) {
      const std::string unit = e["unit"].get<std::string>();
      char at[48] = "";
      if (e["max_abs_error"].get<double>() > 0) std::snprintf(at, sizeof at, " at t = %.6g s", e["t_of_max_error_s"].get<double>());
      std::printf("  %-32s max |error| %.3g %s (%.3g %% of range)%s, rms %.3g\n", name.c_str(),
                  e["max_abs_error"].get<double>(), unit.c_str(), 100 * e["max_rel_error"].get<double>(), at,
                  e["rms_abs_error"].get<double>());
      // A known artefact of the coupling: say which, and what the error is without it.
      const double range = e["reference_range"].get<double>();
      auto percent = [&](double v) { return range > 0 ? 100 * v / range : 0.0; };
      if (e.value("max_abs_error_at_jump", false))
        std::printf("  %-32s   at a jump of the reference (t = %.6g s) that a Jacobi edge crosses one macro step late;"
                    " away from the %d jump(s): max |error| %.3g %s (%.3g %%)\n", "", e["t_jump_s"].get<double>(),
                    e["reference_jumps"].get<int>(), e["max_abs_error_away_from_jumps"].get<double>(), unit.c_str(),
                    percent(e["max_abs_error_away_from_jumps"].get<double>()));
      else if (e.value("one_step_late", false))
        std::printf("  %-32s   the co-simulation is the reference one macro step late (a Jacobi edge): shifted by one step,"
                    " max |difference| %.3g %s\n", "", e["max_abs_error_shifted_one_step"].get<double>(), unit.c_str());
    }
    tools::print_figures(summary["report"]);
    print_realtime_summary(summary);
    if (!summary["events"].empty()) {
      std::map<std::string, int> counts;
      for (const auto& e : summary["events"]) ++counts[e["node"].get<std::string>() + "." + e.value("kind", "?")];
      for (const auto& [kind, n] : counts)
        std::printf("  events: %d x %s (reference: %d; details in the summary JSON)\n", n, kind.c_str(),
                    summary["reference"]["event_counts"].value(kind, 0));
    }
    print_solver_health(summary["nodes"]);
    if (summary.contains("adaptive_step") && summary["adaptive_step"].contains("suggested_scales")) {
      std::string scales;
      for (const auto& [participant, fields] : summary["adaptive_step"]["suggested_scales"].items()) {
        std::string inner;
        for (const auto& [field, range] : fields.items()) {
          char buf[96];
          std::snprintf(buf, sizeof buf, "%s%s: %.3g", inner.empty() ? "" : ", ", field.c_str(), range.get<double>());
          inner += buf;
        }
        scales += (scales.empty() ? "" : ", ") + participant + ": {" + inner + "}";
      }
      std::printf("  adaptive step without time.scales: each signal's error was measured against its range so far, small while it\n"
                  "    first rises (docs/accuracy.md). This run's ranges (SI), to write in the scene's time section:\n"
                  "    scales: {%s}\n", scales.c_str());
    }
    std::printf("  run folder: %s\n", run_dir.c_str());
    return 0;
  }
  std::fprintf(stderr, "mechsim: run failed: %s%s\n", out.reason.c_str(),
               out.failed_node.empty() || out.failed_node.find(',') != std::string::npos
                   ? ""
                   : (" (last step " + std::to_string(out.failed_step) + ")").c_str());
  std::fprintf(stderr, "mechsim: the run is incomplete (summary.json: \"complete\": false)\n");
  print_solver_health(summary["nodes"]);
  std::fprintf(stderr, "mechsim: all node processes stopped; logs in %s\n", run_dir.c_str());
  return out.exit_code;
}

}  // namespace mechsim::launch

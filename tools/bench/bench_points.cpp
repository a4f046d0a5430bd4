#include "bench_runner.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <span>

#include "assessment_json.h"
#include "elapsed.h"
#include "mechsim/assess/report_figures.h"
#include "mechsim/assess/signal_compare.h"
#include "mechsim/cosim/inproc_run.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/scene_plan.h"

namespace mechsim::bench {

namespace fs = std::filesystem;

std::vector<std::string> Bench::run_overrides(const RunSpec& r, bool with_solver) const {
  std::vector<std::string> o = opt_.overrides;
  o.push_back("mode=lockstep");
  if (r.adaptive()) {
    // The scene's own adaptive settings, or the defaults of `step: adaptive`; sampled blocks
    // keep the scene's sample time.
    o.push_back("time.step=adaptive");
    o.push_back("time.tolerance=" + num(r.tolerance, "%.9g"));
    o.push_back("time.max=" + num(adaptive_max_, "%.17g"));
    o.push_back("time.min=" + num(adaptive_min_, "%.17g"));
    o.push_back("time.initial=" + num(adaptive_initial_, "%.17g"));
    if (const auto it = adaptive_scales_.find(r.variant); it != adaptive_scales_.end())
      for (const auto& [field, scale] : it->second) o.push_back("time.scales." + field + "=" + num(scale, "%.17g"));
  } else {
    o.push_back("time.step=" + time_text(r.h));
    // A sampled block whose sample time is the macro step keeps sampling at each exchange.
    for (const auto& p : sampled_) o.push_back("participants." + p + ".params.sample_time=" + time_text(r.h));
  }
  if (with_solver)
    for (const auto& p : participants_) {
      o.push_back("participants." + p + ".solver.method=" + r.solver);
      o.push_back("participants." + p + ".solver.rtol=" + num(r.rtol, "%.3g"));
      o.push_back("participants." + p + ".solver.atol=" + num(r.rtol * 1e-3, "%.3g"));
    }
  return o;
}

// The reference at H for the variant's coupling element (the composer evaluates the element
// once from both sides, whatever the reconstruction, order or levels: one reference per
// element scheme and H).
Reference& Bench::reference(int variant, double h) {
  std::string key = "none";
  const YAML::Node conns = variants_[variant].document["connections"];
  for (const auto& c : conns)
    if (c["coupling"]) key = c["coupling"]["scheme"] ? c["coupling"]["scheme"].as<std::string>() : "?";
  auto& slot = refs_[{key, h}];
  if (slot) return *slot;
  slot = std::make_unique<Reference>();
  RunSpec r{variant, h, "", 0, ""};
  try {
    slot->scene = std::make_unique<config::Scene>(config::load_scene(variant_files_[variant], run_overrides(r, false)));
    cosim::ScenePlan plan = cosim::ScenePlan::build(*slot->scene);
    slot->run = cosim::run_reference(plan);
    slot->accuracy = cosim::estimate_reference_error(*slot->scene, slot->run);
    slot->accuracy_json = tools::reference_accuracy_json(*slot->scene, slot->run, slot->accuracy);
  } catch (const std::exception& e) {
    slot->error = e.what();
  }
  return *slot;
}

// The reference of an adaptive point: at the instants its run took (the node logs in run_dir),
// never shared with another run.
void Bench::adaptive_reference(const RunSpec& r, const std::string& run_dir, Reference& ref) {
  try {
    ref.scene = std::make_unique<config::Scene>(config::load_scene(variant_files_[r.variant], run_overrides(r, false)));
    cosim::ScenePlan plan = cosim::ScenePlan::build(*ref.scene);
    const std::vector<double> instants = cosim::run_instants(plan, run_dir);
    ref.run = cosim::run_reference_at(plan, instants);
    ref.accuracy = cosim::estimate_reference_error(*ref.scene, ref.run);
    ref.accuracy_json = tools::reference_accuracy_json(*ref.scene, ref.run, ref.accuracy);
  } catch (const std::exception& e) {
    ref.error = e.what();
  }
}

void Bench::compare(const config::Scene& scene, const Reference& ref, const std::vector<std::string>& participants,
                    const std::function<std::string(const std::string&)>& log_path, RunResult& res) {
  std::map<std::string, cosim::OutputLog> logs;
  for (const auto& p : participants) logs[p] = cosim::read_output_log(log_path(p));
  const auto& t = ref.run.log.data[0];
  double worst_rms = -1, worst_max = -1;
  for (const auto& sig : scene.compare) {
    const std::string name = sig.full_name();
    const auto& log = logs.at(sig.participant);
    const int cc = log.column(sig.output), rc = ref.run.log.column(name);
    if (cc < 0 || rc < 0) continue;
    const auto& c = log.data[cc];
    const auto& r = ref.run.log.data[rc];
    if (c.size() != r.size()) {
      res.status = "failed";
      res.reason = name + ": node log has " + std::to_string(c.size()) + " rows, reference " + std::to_string(r.size());
      return;
    }
    const bool c_nan = std::all_of(c.begin(), c.end(), [](double v) { return std::isnan(v); });
    const bool r_nan = std::all_of(r.begin(), r.end(), [](double v) { return std::isnan(v); });
    if (c_nan || r_nan) {
      res.signals[name] = {{"computed", false}};  // a field this configuration does not compute
      continue;
    }
    const assess::SignalError e = assess::compare_signal(t, c, r);
    const double ref_max = ref.accuracy.max_abs_of(name), ref_rms = ref.accuracy.rms_abs_of(name);
    const double scale = e.range > 0 ? e.range : 1.0;
    // Refused when not larger than the reference's own error: such a figure says more about
    // the reference than about the co-simulation.
    const bool max_below = e.finite && !(e.max_abs > ref_max);
    const bool rms_below = e.finite && !(e.rms_abs > ref_rms);
    const double inf = std::numeric_limits<double>::infinity();
    const double max_rel = e.finite ? e.max_rel : inf, rms_rel = e.finite ? e.rms_rel : inf;
    res.signals[name] = {
        {"max_abs_error", max_below ? json(nullptr) : finite_or_null(e.max_abs)},
        {"rms_abs_error", rms_below ? json(nullptr) : finite_or_null(e.rms_abs)},
        {"max_rel_error", max_below ? json(nullptr) : finite_or_null(max_rel)},
        {"rms_rel_error", rms_below ? json(nullptr) : finite_or_null(rms_rel)},
        {"below_reference_accuracy", {{"max", max_below}, {"rms", rms_below}}},
        {"reference_error", {{"max_abs", ref_max}, {"rms_abs", ref_rms}}},
        {"reference_range", e.range},
        {"t_of_max_error_s", e.t_of_max},
        {"finite", e.finite}};
    // The worst signal: a refused one counts with its bound (the reference's error).
    const double rms_value = rms_below ? ref_rms / scale : rms_rel;
    const double max_value = max_below ? ref_max / scale : max_rel;
    if (rms_value > worst_rms) {
      worst_rms = rms_value;
      res.rms_below_reference = rms_below;
      res.rms_rel = rms_below ? kNaN : rms_rel;
      res.rms_rel_bound = rms_below ? rms_value : kNaN;
      res.worst_signal = name;
    }
    if (max_value > worst_max) {
      worst_max = max_value;
      res.max_below_reference = max_below;
      res.max_rel = max_below ? kNaN : max_rel;
    }
  }
  auto cosim_series = [&](const config::SignalRef& r) -> std::span<const double> {
    auto it = logs.find(r.participant);
    if (it == logs.end()) return {};
    const int c = it->second.column(r.output);
    return c < 0 ? std::span<const double>{} : std::span<const double>(it->second.data[c]);
  };
  const assess::SeriesLookup reference_lookup = [&](const config::SignalRef& r) -> std::span<const double> {
    const int c = ref.run.log.column(r.full_name());
    return c < 0 ? std::span<const double>{} : std::span<const double>(ref.run.log.data[c]);
  };
  try {
    res.report = tools::report_figures_json(assess::report_figures(scene, t, cosim_series, &reference_lookup));
  } catch (const std::exception& e) {
    res.report = {{"error", e.what()}};
  }
}

std::vector<std::pair<std::string, double>> Bench::reference_scales(int variant, double h) {
  Reference& ref = reference(variant, h);
  std::vector<std::pair<std::string, double>> out;
  if (!ref.error.empty() || !ref.scene) return out;
  try {
    // Each quantity once (ScenePlan::scaled_quantities).
    const auto add = [&](const std::string& name) {
      const int c = ref.run.log.column(name);
      if (c < 0) return;
      if (const double range = cosim::finite_range(ref.run.log.data[static_cast<std::size_t>(c)]); range > 0)
        out.emplace_back(name, range);
    };
    const cosim::ScenePlan plan = cosim::ScenePlan::build(*ref.scene);
    for (const auto& [participant, field] : plan.scaled_quantities()) add(participant + "." + field);
  } catch (const std::exception&) {
    out.clear();
  }
  return out;
}

// Short runs are timed again (the outputs are the same bit for bit) and the fastest is
// kept: thread start and scheduling noise are a large part of a 50 ms run. Up to ten runs,
// until half a second has gone by; and every run at least --repeat times (runs of a second
// scatter by some 20 % on a shared machine). Returns the fastest wall time, `first_wall`
// included.
double Bench::fastest_of_repeats(const config::Scene& scene, cosim::InprocRunOptions io, bool first_ok, double first_wall) {
  double fastest = first_wall, timed = first_wall;
  for (int repeat = 1; repeat < std::max(10, opt_.repeat) && first_ok &&
                       (repeat < opt_.repeat || (fastest < 0.25 && timed < 0.5));
       ++repeat) {
    io.run_id = ++run_counter_;
    const auto t1 = Clock::now();
    const cosim::InprocRunResult again = cosim::run_inproc(scene, io);
    const double wall = seconds_since(t1);
    timed += wall;
    if (again.ok) fastest = std::min(fastest, wall);
  }
  return fastest;
}

// The node solvers' statistics of a run, summed over the nodes.
json solver_totals(const cosim::InprocRunResult& ir) {
  long steps = 0, rhs = 0, etf = 0, nlf = 0, roots = 0;
  for (const auto& n : ir.nodes) {
    steps += n.last.solver_steps;
    rhs += n.last.rhs_evals;
    etf += n.last.error_test_failures;
    nlf += n.last.nonlinear_failures;
    roots += n.last.roots_found;
  }
  return {{"steps", steps}, {"rhs_evals", rhs}, {"error_test_failures", etf}, {"nonlinear_failures", nlf},
          {"roots_found", roots}};
}

// The macro steps an adaptive run took: the rows of a node's log after the first.
void Bench::steps_taken(const std::string& run_dir, RunResult& res) const {
  try {
    const cosim::OutputLog log = cosim::read_output_log(run_dir + "/" + participants_.front() + ".outputs.bin");
    const auto& t = log.data.at(0);
    res.macro_steps = t.empty() ? 0 : static_cast<long>(t.size()) - 1;
    for (std::size_t k = 1; k < t.size(); ++k) {
      const double h = t[k] - t[k - 1];
      res.step_min_s = k == 1 ? h : std::min(res.step_min_s, h);
      res.step_max_s = k == 1 ? h : std::max(res.step_max_s, h);
    }
  } catch (const std::exception&) {
    res.macro_steps = 0;
  }
}

RunResult Bench::run_inproc_point(const RunSpec& r, const std::string& run_dir) {
  RunResult res;
  res.run_dir = run_dir;
  // A fixed H: the reference at H (shared by the runs at H); adaptive: its own, after the run.
  Reference adaptive_ref;
  Reference& ref = r.adaptive() ? adaptive_ref : reference(r.variant, r.h);
  if (!ref.error.empty()) {
    res.status = "refused";
    res.reason = ref.error;
    return res;
  }
  std::unique_ptr<config::Scene> scene;
  try {
    scene = std::make_unique<config::Scene>(config::load_scene(variant_files_[r.variant], run_overrides(r, true)));
    // Validation (run_inproc builds its own), and the grid's step count (events land on it;
    // 0 for an adaptive step, counted from the log after the run).
    res.macro_steps = static_cast<long>(cosim::ScenePlan::build(*scene).grid()->steps());
  } catch (const std::exception& e) {
    res.status = "refused";
    res.reason = e.what();
    return res;
  }
  fs::create_directories(run_dir);
  cosim::InprocRunOptions io;
  io.run_dir = run_dir;
  io.run_id = ++run_counter_;
  cosim::InprocRunResult ir;
  // Wall time of the whole in-process run, as measured here: thread start, readiness and
  // the steps (run_inproc's own figure polls at 20 ms, too coarse for short runs).
  const auto t0 = Clock::now();
  try {
    ir = cosim::run_inproc(*scene, io);
  } catch (const std::exception& e) {
    res.status = "refused";
    res.reason = e.what();
    return res;
  }
  res.wall_time_s = fastest_of_repeats(*scene, io, ir.ok, seconds_since(t0));
  res.solver = solver_totals(ir);
  if (r.adaptive()) steps_taken(run_dir, res);
  if (!ir.ok) {
    res.status = ir.diverged ? "diverged" : "failed";
    res.reason = ir.reason;
    return res;
  }
  res.status = "ok";
  res.completed = true;
  if (r.adaptive()) {
    adaptive_reference(r, run_dir, ref);
    if (!ref.error.empty()) {
      res.status = "refused";
      res.reason = "reference: " + ref.error;
      return res;
    }
    res.reference = {{"step_s", nullptr}, {"tolerance", r.tolerance}, {"instants", ref.run.log.data.empty() ? 0 : ref.run.log.data[0].size()},
                     {"rtol", ref.run.rtol}, {"wall_time_s", ref.run.wall_time_s}, {"accuracy", ref.accuracy_json}};
  }
  try {
    compare(*scene, ref, participants_, [&](const std::string& p) { return run_dir + "/" + p + ".outputs.bin"; }, res);
  } catch (const std::exception& e) {
    res.status = "failed";
    res.reason = std::string("comparison: ") + e.what();
  }
  if (res.status == "ok" && !std::isfinite(res.rms_rel) && !res.rms_below_reference) res.status = "diverged";
  // A run that grows without tripping the divergence guard within the scene's time: an RMS
  // error larger than the signal's whole range is no measurement of accuracy.
  if (res.status == "ok" && res.rms_rel > 1.0) {
    res.status = "unstable";
    res.reason = res.worst_signal + ": RMS error " + num(res.rms_rel) + " x the reference range";
  }
  return res;
}

}  // namespace mechsim::bench

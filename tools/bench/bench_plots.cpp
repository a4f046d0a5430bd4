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

#include <set>

#include "plot.h"

namespace mechsim::bench {

namespace fs = std::filesystem;

namespace {

// One log-log panel of error curves against `xlabel`.
plot::Panel panel_of(const Curves& c, const std::string& title, const std::string& xlabel) {
  plot::Panel p;
  p.title = title;
  p.xlabel = xlabel;
  p.ylabel = "RMS error / reference range (worst compared signal)";
  p.logx = p.logy = true;
  for (const auto& [name, pts] : c) {
    plot::Series s;
    s.label = name;
    s.style = "linespoints";
    for (const auto& [x, y] : pts) {
      s.x.push_back(x);
      s.y.push_back(y);
    }
    p.series.push_back(s);
  }
  return p;
}

}  // namespace

// Curves of the fixed-H rows of a sweep ("solver": (scheme, solver); "tolerance": (scheme,
// rtol) of cvode_bdf), RMS error against wall time or H; the points follow H (sorted),
// whatever the wall time does.
Curves Bench::sweep_curves(const std::string& sweep, bool by_h) const {
  Curves c;
  std::map<std::string, std::map<double, double>> yv;
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    if (specs_[i].sweep != sweep && !(sweep == "tolerance" && specs_[i].solver == "cvode_bdf")) continue;
    const auto& res = results_[i];
    if (res.status != "ok" || !std::isfinite(res.rms_rel)) continue;
    std::string name = variants_[specs_[i].variant].name + " " + specs_[i].solver;
    if (sweep == "tolerance") name = variants_[specs_[i].variant].name + " rtol " + num(specs_[i].rtol, "%.0e");
    c[name].push_back({specs_[i].h, res.wall_time_s});
    yv[name][specs_[i].h] = res.rms_rel;
  }
  Curves out;
  for (auto& [k, pts] : c) {
    std::sort(pts.begin(), pts.end());
    for (const auto& [h, wall] : pts) out[k].push_back({by_h ? h : wall, yv[k][h]});
  }
  return out;
}

// The adaptive curves (cvode_bdf at --rtol): points along a curve are tolerances, loosest
// first; RMS or max error of the worst compared signal against wall time.
Curves Bench::adaptive_curves(bool max_error) const {
  Curves c;
  for (std::size_t i = 0; i < adaptive_specs_.size(); ++i) {
    const auto& res = adaptive_results_[i];
    const double e = max_error ? res.max_rel : res.rms_rel;
    if (res.status != "ok" || !std::isfinite(e)) continue;
    c[scheme_name(adaptive_specs_[i])].push_back({res.wall_time_s, e});
  }
  return c;
}

// The max error (the 5x target of the adaptive step) against wall time: fixed-H schemes
// and adaptive curves, cvode_bdf at --rtol.
plot::Panel Bench::max_error_panel() const {
  std::map<std::string, std::map<double, std::pair<double, double>>> fixed;  // scheme -> H -> (wall, max)
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    const auto& res = results_[i];
    if (specs_[i].sweep != "solver" || specs_[i].solver != "cvode_bdf" || specs_[i].rtol != opt_.rtol) continue;
    if (res.status != "ok" || !std::isfinite(res.max_rel)) continue;
    fixed[variants_[specs_[i].variant].name][specs_[i].h] = {res.wall_time_s, res.max_rel};
  }
  Curves sub;
  for (const auto& [name, by_h] : fixed)
    for (const auto& [h, p] : by_h) sub[name].push_back(p);
  for (const auto& [name, pts] : adaptive_curves(true)) sub[name] = pts;
  plot::Panel p = panel_of(sub, "max error: fixed H and adaptive (cvode_bdf, rtol " + num(opt_.rtol, "%.0e") + ")", "wall time [s]");
  p.ylabel = "max error / reference range (worst compared signal)";
  return p;
}

// Work against precision: one panel per node solver (a curve per scheme), the max error
// when there are adaptive points, then the tolerance sweep.
plot::Figure Bench::work_precision_figure() const {
  const bool any_adaptive = !adaptive_curves(false).empty() || !adaptive_curves(true).empty();
  plot::Figure wp;
  wp.title = scene_name_ + (any_adaptive ? ": work-precision (in process; points along a curve: H, adaptive: tolerances)"
                                          : ": work-precision (in-process runs; points along a curve are macro steps H)");
  wp.height_px_per_panel = 420;
  const auto all = sweep_curves("solver", false);
  std::vector<std::string> solver_names;
  for (const auto& sp : specs_)
    if (sp.sweep == "solver" && std::find(solver_names.begin(), solver_names.end(), sp.solver) == solver_names.end())
      solver_names.push_back(sp.solver);
  for (const auto& solver : solver_names) {
    Curves sub;
    const std::string suffix = " " + solver;
    for (const auto& [name, pts] : all)
      if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
        sub[name.substr(0, name.size() - suffix.size())] = pts;
    if (solver == "cvode_bdf")
      for (const auto& [name, pts] : adaptive_curves(false)) sub[name] = pts;
    wp.panels.push_back(panel_of(sub, solver + " in every node (rtol " + num(opt_.rtol, "%.0e") + ")", "wall time [s]"));
  }
  if (any_adaptive) wp.panels.push_back(max_error_panel());
  // The tolerance panel keeps the baseline, the shipped scheme and the best one readable.
  auto tol = sweep_curves("tolerance", false);
  std::set<std::string> keep;
  for (const auto& v : variants_)
    if (v.zero_order_hold_jacobi || v.shipped) keep.insert(v.name);
  if (best_scheme_) keep.insert(*best_scheme_);
  for (auto it = tol.begin(); it != tol.end();) {
    const std::string scheme = it->first.substr(0, it->first.find(" rtol "));
    it = keep.count(scheme) ? std::next(it) : tol.erase(it);
  }
  if (!tol.empty()) wp.panels.push_back(panel_of(tol, "tolerance sweep (cvode_bdf; baseline, shipped and best scheme)", "wall time [s]"));
  return wp;
}

// The error against H per scheme (cvode_bdf), labelled with the observed orders.
plot::Figure Bench::error_vs_step_figure(const json& orders) const {
  plot::Figure ord;
  ord.title = scene_name_ + ": error against macro step (cvode_bdf)";
  ord.height_px_per_panel = 520;
  Curves bdf;
  for (auto& [name, pts] : sweep_curves("solver", true))
    if (name.size() > 10 && name.substr(name.size() - 10) == " cvode_bdf") {
      std::string label = name.substr(0, name.size() - 10);
      for (const auto& o : orders)
        if (o["scheme"] == label && o["order"].is_number()) label += " (order " + num(o["order"].get<double>(), "%.2f") + ")";
      bdf[label] = pts;
    }
  ord.panels.push_back(panel_of(bdf, "observed order: slope of log error against log H", "macro step H [s]"));
  return ord;
}

void Bench::plots(const json& orders) {
  if (opt_.plots_dir.empty()) return;
  fs::create_directories(opt_.plots_dir);
  std::string why;
  const std::string wp_path = opt_.plots_dir + "/" + scene_name_ + "_work_precision.png";
  if (!plot::write_png(work_precision_figure(), wp_path, &why))
    std::fprintf(stderr, "mechsim bench: no plot %s: %s\n", wp_path.c_str(), why.c_str());
  const std::string ord_path = opt_.plots_dir + "/" + scene_name_ + "_error_vs_step.png";
  if (!plot::write_png(error_vs_step_figure(orders), ord_path, &why))
    std::fprintf(stderr, "mechsim bench: no plot %s: %s\n", ord_path.c_str(), why.c_str());
}

}  // namespace mechsim::bench

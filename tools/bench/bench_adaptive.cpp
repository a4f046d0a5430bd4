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

#include "elapsed.h"

namespace mechsim::bench {

namespace fs = std::filesystem;

// The swept H nearest the scene's step.
double Bench::h_nearest_scene_step() const {
  double h_own = grid_.front();
  for (double h : grid_)
    if (std::abs(std::log(h / h0_)) < std::abs(std::log(h_own / h0_))) h_own = h;
  return h_own;
}

// The variant with the smallest max error of cvode_bdf at --rtol at H (an error below the
// reference's own counting as 0, the first variant on a tie); -1 when none ran through.
int Bench::best_fixed_variant_at(double h, double& best_error) const {
  int best = -1;
  best_error = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    const auto& r = specs_[i];
    const auto& res = results_[i];
    if (r.sweep != "solver" || r.solver != "cvode_bdf" || r.rtol != opt_.rtol || r.h != h || res.status != "ok") continue;
    const double e = res.max_below_reference ? 0.0 : res.max_rel;
    if (std::isfinite(e) && e < best_error) {
      best_error = e;
      best = r.variant;
    }
  }
  return best;
}

// Adaptive points: the shipped scheme, its orders with every Jacobi edge quadratic
// (SchemeVariant::shipped_quadratic), and the best fixed-H scheme at the scene's H (the
// swept H nearest it): the smallest max error of cvode_bdf at --rtol, an error below the
// reference's own counting as 0, the first variant on a tie; cvode_bdf at --rtol, with the
// scene's adaptive settings or the defaults of `step: adaptive`. Fills adaptive_choice_,
// the scales and adaptive_specs_.
void Bench::choose_adaptive_points() {
  tolerances_ = opt_.tolerances ? *opt_.tolerances
                                : (opt_.quick ? std::vector<double>{1e-2, 1e-3} : std::vector<double>{1e-2, 3e-3, 1e-3, 3e-4, 1e-4});
  // The scene's adaptive settings (time.max, min, initial), or the defaults a scene gets
  // with `step: adaptive` alone.
  try {
    std::vector<std::string> o = opt_.overrides;
    o.push_back("time.step=adaptive");
    const config::Scene s = config::load_scene(variant_files_[0], o);
    adaptive_max_ = scene_adaptive_ ? scene_adaptive_->max : s.time.adaptive->max;
    adaptive_min_ = scene_adaptive_ ? scene_adaptive_->min : s.time.adaptive->min;
    adaptive_initial_ = scene_adaptive_ ? scene_adaptive_->initial : s.time.adaptive->initial;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim bench: no adaptive points: %s\n", e.what());
  }
  const double h_own = h_nearest_scene_step();
  double best_error = 0;
  const int best = best_fixed_variant_at(h_own, best_error);
  std::vector<int> chosen;
  for (int v = 0; v < static_cast<int>(variants_.size()); ++v)
    if (variants_[v].shipped) {
      chosen.push_back(v);
      adaptive_choice_.push_back({{"variant", variants_[v].name}, {"why", "shipped"}});
    }
  // The shipped orders with quadratic Jacobi edges (scheme_variants): an error-controlled
  // step may take longer steps with the higher-order predictor.
  for (int v = 0; v < static_cast<int>(variants_.size()); ++v)
    if (variants_[v].shipped_quadratic && !variants_[v].shipped) {
      chosen.push_back(v);
      adaptive_choice_.push_back({{"variant", variants_[v].name}, {"why", "the shipped orders, Jacobi edges quadratic"}});
    }
  if (best >= 0 && std::find(chosen.begin(), chosen.end(), best) == chosen.end()) {
    chosen.push_back(best);
    adaptive_choice_.push_back({{"variant", variants_[best].name},
                                {"why", "best fixed-H max error at H " + time_text(h_own) + " (cvode_bdf, rtol " + num(opt_.rtol, "%.0e") + ")"},
                                {"max_rel_at_h", finite_or_null(best_error)}});
  } else if (best >= 0) {
    for (auto& c : adaptive_choice_)
      if (c["variant"] == variants_[best].name)
        c["why"] = c["why"].get<std::string>() + "; also the best fixed-H max error at H " + time_text(h_own);
  }
  if (tolerances_.empty() || !(adaptive_max_ > 0)) adaptive_choice_ = json::array();  // --tolerances none
  // Scales: the scene's; without any, each coupled field's range in the reference at the
  // scene's H, as an engineer writes them after one run (docs/accuracy.md).
  for (int v : chosen) {
    if (scene_adaptive_ && !scene_adaptive_->scales.empty()) {
      adaptive_scales_[v] = scene_adaptive_->scales;
    } else {
      adaptive_scales_[v] = reference_scales(v, h_own);
      adaptive_scales_from_ = "reference range";
    }
  }
  if (adaptive_choice_.empty()) chosen.clear();
  for (int v : chosen)
    for (double tol : tolerances_) adaptive_specs_.push_back({v, 0.0, "cvode_bdf", opt_.rtol, "adaptive", tol});
}

void Bench::run_adaptive_points() {
  adaptive_results_.resize(adaptive_specs_.size());
  for (std::size_t i = 0; i < adaptive_specs_.size(); ++i) {
    const RunSpec& r = adaptive_specs_[i];
    const std::string dir = opt_.work_dir + "/adaptive-" + std::to_string(i);
    adaptive_results_[i] = run_inproc_point(r, dir);
    const RunResult& res = adaptive_results_[i];
    std::fprintf(stderr, "[adaptive %zu/%zu %5.0f s] %-22s tol %-6s %-11s rtol %-6s %-8s steps %-7ld max %-10s rms %-10s wall %s s%s%s\n",
                 i + 1, adaptive_specs_.size(), seconds_since(t_start_), variants_[r.variant].name.c_str(),
                 tol_text(r.tolerance).c_str(), r.solver.c_str(), num(r.rtol, "%.0e").c_str(), res.status.c_str(), res.macro_steps,
                 res.max_below_reference ? "<ref" : num(res.max_rel).c_str(),
                 res.rms_below_reference ? "<ref" : num(res.rms_rel).c_str(), num(res.wall_time_s).c_str(),
                 res.reason.empty() ? "" : ": ", res.reason.substr(0, 200).c_str());
    if (!opt_.keep_work_dir) {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  }
}

// A fixed-H row of the comparison: cvode_bdf at --rtol, status ok.
bool Bench::is_fixed_row(std::size_t i) const {
  return specs_[i].solver == "cvode_bdf" && specs_[i].rtol == opt_.rtol && results_[i].status == "ok";
}

// The fixed-H rows in (wall time, error), every scheme and H; rows below reference accuracy
// only by their wall time.
FixedEnvelope Bench::fixed_envelope(bool use_max) const {
  FixedEnvelope env;
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    if (!is_fixed_row(i)) continue;
    const auto& res = results_[i];
    if (use_max ? res.max_below_reference : res.rms_below_reference) {
      env.below_walls.push_back(res.wall_time_s);
      continue;
    }
    const double e = use_max ? res.max_rel : res.rms_rel;
    if (!(e > 0) || !std::isfinite(e) || !(res.wall_time_s > 0)) continue;
    env.points.push_back({res.wall_time_s, e});
    env.rows.push_back(i);
    env.wall_lo = std::isnan(env.wall_lo) ? res.wall_time_s : std::min(env.wall_lo, res.wall_time_s);
    env.wall_hi = std::isnan(env.wall_hi) ? res.wall_time_s : std::max(env.wall_hi, res.wall_time_s);
  }
  return env;
}

// The same scheme at fixed H in (macro steps, error): what adapting the step alone buys,
// free of the wall-time noise of short runs.
std::vector<std::pair<double, double>> Bench::same_scheme_by_steps(int variant, bool use_max) const {
  std::vector<std::pair<double, double>> same;
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    if (!is_fixed_row(i) || specs_[i].variant != variant || (use_max ? results_[i].max_below_reference : results_[i].rms_below_reference)) continue;
    const double e = use_max ? results_[i].max_rel : results_[i].rms_rel;
    if (e > 0 && std::isfinite(e) && results_[i].macro_steps > 0) same.push_back({static_cast<double>(results_[i].macro_steps), e});
  }
  return same;
}

// One adaptive point against the fixed-H envelope at its wall time, and against the same
// scheme at its number of macro steps.
json Bench::adaptive_point_vs_fixed(std::size_t j, bool use_max, const FixedEnvelope& env,
                                    const std::vector<std::pair<double, double>>& same) const {
  const auto& r = adaptive_specs_[j];
  const auto& res = adaptive_results_[j];
  const bool below = use_max ? res.max_below_reference : res.rms_below_reference;
  const double e = use_max ? res.max_rel : res.rms_rel;
  json p{{"tolerance", r.tolerance},
         {"status", res.status},
         {"macro_steps", res.macro_steps},
         {"wall_time_s", finite_or_null(res.wall_time_s)},
         {"adaptive_error", finite_or_null(e)},
         {"adaptive_below_reference_accuracy", below},
         {"fixed_error", nullptr},
         {"factor", nullptr}};
  if (res.status != "ok") {
    p["note"] = "adaptive run " + res.status;
  } else if (below) {
    p["note"] = "adaptive error below reference accuracy: left out of the factor";
  } else if (!(e > 0) || !std::isfinite(e)) {
    p["note"] = "no finite adaptive error";
  } else {
    int lo = -1, hi = -1;
    const double fe = envelope_at(env.points, res.wall_time_s, &lo, &hi);
    if (!std::isfinite(fe)) {
      p["fixed_error"] = "outside";
      p["note"] = "adaptive wall time outside the fixed-H rows' wall time range";
    } else {
      p["fixed_error"] = fe;
      json between = json::array();
      for (int k : {lo, hi}) {
        if (k < 0 || (k == hi && hi == lo)) continue;
        const std::size_t i = env.rows[k];
        between.push_back({{"scheme", variants_[specs_[i].variant].name}, {"step_s", specs_[i].h},
                           {"wall_time_s", results_[i].wall_time_s}, {"error", env.points[k].second}});
      }
      p["fixed_envelope_corners"] = between;
      const bool fixed_below = std::any_of(env.below_walls.begin(), env.below_walls.end(),
                                           [&](double w) { return w <= res.wall_time_s; });
      if (fixed_below) p["note"] = "a fixed-H row at no more wall time is below reference accuracy: left out of the factor";
      else p["factor"] = fe / e;
    }
  }
  p["fixed_error_same_scheme_at_equal_steps"] = nullptr;
  p["factor_at_equal_steps"] = nullptr;
  if (res.status == "ok" && !below && e > 0 && std::isfinite(e) && res.macro_steps > 0) {
    const double fs = envelope_at(same, static_cast<double>(res.macro_steps), nullptr, nullptr);
    if (std::isfinite(fs)) {
      p["fixed_error_same_scheme_at_equal_steps"] = fs;
      p["factor_at_equal_steps"] = fs / e;
    }
  }
  return p;
}

// The adaptive points of one variant against fixed H, max or RMS error, with the best factors.
json Bench::adaptive_curve_vs_fixed(int variant, bool use_max) const {
  const FixedEnvelope env = fixed_envelope(use_max);
  const auto same = same_scheme_by_steps(variant, use_max);
  json f{{"points", json::array()},
         {"fixed_rows", env.points.size()},
         {"fixed_rows_below_reference_accuracy", env.below_walls.size()},
         {"fixed_wall_time_range_s", {finite_or_null(env.wall_lo), finite_or_null(env.wall_hi)}}};
  double best = kNaN, best_steps = kNaN;
  json best_at;
  for (std::size_t j = 0; j < adaptive_specs_.size(); ++j) {
    if (adaptive_specs_[j].variant != variant) continue;
    json p = adaptive_point_vs_fixed(j, use_max, env, same);
    if (p["factor"].is_number()) {
      const double factor = p["factor"].get<double>();
      if (!(factor <= best)) {
        best = factor;
        best_at = adaptive_specs_[j].tolerance;
      }
    }
    if (p["factor_at_equal_steps"].is_number()) {
      const double factor = p["factor_at_equal_steps"].get<double>();
      if (!(factor <= best_steps)) best_steps = factor;
    }
    f["points"].push_back(p);
  }
  f["best_factor_at_equal_steps"] = finite_or_null(best_steps);
  f["best_factor"] = finite_or_null(best);
  f["best_at_tolerance"] = best_at;
  f["target_5x_met"] = std::isfinite(best) ? json(best >= 5) : json(nullptr);
  return f;
}

// Adaptive against fixed H at equal wall time: for each adaptive point, the lower envelope
// of the fixed-H rows (cvode_bdf at --rtol, every scheme and H, status ok) in (wall time,
// error), interpolated log-log at the point's wall time, over the point's error.
json Bench::adaptive_vs_fixed() const {
  json adaptive_vs_fixed = {
      {"definition",
       "per adaptive point: factor = fixed_error / adaptive_error, fixed_error the lower envelope of (wall_time_s, error) "
       "over the fixed-H rows with solver cvode_bdf at the bench's rtol and status ok (every scheme and H), interpolated "
       "log-log between the envelope's corners at the adaptive run's wall time; no factor outside the fixed rows' wall "
       "time range ('outside'), nor where an error is below reference accuracy (the adaptive point's, or a fixed row's "
       "at no more wall time: such rows are left out of the envelope); best_factor over the points, target_5x_met = "
       "best_factor >= 5. 'max' is the max_rel error of the worst compared signal, 'rms' the rms_rel one. Beside it, "
       "factor_at_equal_steps: the same scheme's fixed-H error interpolated log-log at the adaptive run's macro steps, "
       "over the adaptive error (what adapting the step buys, free of wall-time noise)"},
      {"solver", "cvode_bdf"},
      {"rtol", opt_.rtol},
      {"time_max_s", adaptive_max_},
      {"time_min_s", adaptive_min_},
      {"time_initial_s", adaptive_initial_},
      {"scales_from", adaptive_scales_from_},
      {"variants", adaptive_choice_},
      {"curves", json::array()}};
  if (tolerances_.empty()) adaptive_vs_fixed["note"] = "no adaptive points (--tolerances none)";
  for (const auto& c : adaptive_choice_) {
    int v = 0;
    while (variants_[v].name != c["variant"]) ++v;
    json curve = adaptive_curve_vs_fixed(v, true);
    curve["scheme"] = "adaptive " + variants_[v].name;
    curve["variant"] = variants_[v].name;
    curve["error"] = "max_rel";
    curve["rms"] = adaptive_curve_vs_fixed(v, false);
    curve["rms"]["error"] = "rms_rel";
    adaptive_vs_fixed["curves"].push_back(curve);
  }
  return adaptive_vs_fixed;
}

}  // namespace mechsim::bench

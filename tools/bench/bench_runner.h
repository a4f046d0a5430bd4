// The bench's runner (bench.h, run_bench): one object per bench holding the sweep, its runs
// and its references, with its parts in files of their own (private to tools/bench):
//   bench.cpp            run(): the order of the bench; the scene, the variants, the grid, the sweep
//   bench_points.cpp     one measured point: overrides, the reference, the in-process run, the errors
//   bench_dds_check.cpp  a point again as `mechsim launch` processes (launch_process.h)
//   bench_adaptive.cpp   the adaptive points and their comparison with fixed H
//   bench_figures.cpp    observed orders, the best scheme against zero-order hold, fit_order, envelope_at
//   bench_report.cpp     the table, the JSON rows and document; bench_plots.cpp the PNGs
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench.h"
#include "bench_text.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/composer.h"
#include "mechsim/cosim/inproc_run.h"
#include "plot.h"

namespace mechsim::bench {

using nlohmann::json;
using Clock = std::chrono::steady_clock;
// Named curves of (x, y) points, for the plots.
using Curves = std::map<std::string, std::vector<std::pair<double, double>>>;

struct RunSpec {
  int variant = 0;
  double h = 0;
  std::string solver;
  double rtol = 0;
  std::string sweep;  // "solver", "tolerance" or "adaptive"
  double tolerance = 0;  // > 0: an adaptive point (time.step: adaptive at this tolerance; h unused)
  bool adaptive() const { return tolerance > 0; }
};

struct Reference {
  cosim::ReferenceRun run;
  cosim::ReferenceAccuracy accuracy;
  json accuracy_json;
  std::unique_ptr<config::Scene> scene;
  std::string error;  // the reference could not be computed
};

struct RunResult {
  std::string status;  // ok, diverged, failed, refused
  std::string reason;
  double wall_time_s = kNaN;
  long macro_steps = 0;
  json solver;
  json signals = json::object();
  json report;
  double rms_rel = kNaN, max_rel = kNaN;  // worst compared signal; NaN when below reference accuracy
  bool rms_below_reference = false, max_below_reference = false;
  double rms_rel_bound = kNaN;  // the reference's own error where the value is refused
  std::string worst_signal;
  std::string run_dir;
  bool completed = false;  // every node ran to the end (whatever the error)
  // Adaptive points: the steps taken (from the node log) and the run's own reference.
  double step_min_s = kNaN, step_max_s = kNaN;
  json reference;
};

// The fixed-H rows the adaptive points are set against, in (wall time, error).
struct FixedEnvelope {
  std::vector<std::pair<double, double>> points;
  std::vector<std::size_t> rows;   // the row (index into the sweep) of each point
  std::vector<double> below_walls;  // wall times of the rows below reference accuracy
  double wall_lo = kNaN, wall_hi = kNaN;
};

class Bench {
 public:
  Bench(const BenchOptions& o, std::ostream& out) : opt_(o), out_(out) {}
  int run();

 private:
  // The parts of run(), in the order it calls them.
  std::unique_ptr<config::Scene> load_base_scene() const;
  bool take_scene(const config::Scene& base);
  bool choose_variants();
  bool plan_sweep(const config::Scene& base);
  void choose_dds_checks();
  void run_sweep();
  void choose_adaptive_points();
  void run_adaptive_points();
  json observed_orders();
  json best_vs_zero_order_hold();
  json adaptive_vs_fixed() const;
  void print_rows();
  void print_findings(const json& orders, const json& ten_x);
  void print_adaptive_vs_fixed(const json& adaptive_vs_fixed);
  void write_json(const json& orders, const json& ten_x, const json& adaptive_vs_fixed, double duration);

  double h_nearest_scene_step() const;
  int best_fixed_variant_at(double h, double& best_error) const;
  double tightest_rtol() const;
  bool is_fixed_row(std::size_t i) const;
  FixedEnvelope fixed_envelope(bool use_max) const;
  std::vector<std::pair<double, double>> same_scheme_by_steps(int variant, bool use_max) const;
  json adaptive_point_vs_fixed(std::size_t j, bool use_max, const FixedEnvelope& env,
                               const std::vector<std::pair<double, double>>& same) const;
  json adaptive_curve_vs_fixed(int variant, bool use_max) const;
  std::string table_line(const std::string& scheme, const std::string& h, const RunSpec& r, const RunResult& res) const;

  std::vector<std::string> run_overrides(const RunSpec& r, bool with_solver) const;
  Reference& reference(int variant, double h);
  void adaptive_reference(const RunSpec& r, const std::string& run_dir, Reference& ref);
  RunResult run_inproc_point(const RunSpec& r, const std::string& run_dir);
  double fastest_of_repeats(const config::Scene& scene, cosim::InprocRunOptions io, bool first_ok, double first_wall);
  void steps_taken(const std::string& run_dir, RunResult& res) const;
  void compare(const config::Scene& scene, const Reference& ref, const std::vector<std::string>& participants,
               const std::function<std::string(const std::string&)>& log_path, RunResult& res);
  json dds_check(const RunSpec& r, const RunResult& inproc);
  json row_json(const RunSpec& r, const RunResult& res) const;
  void plots(const json& orders);
  Curves sweep_curves(const std::string& sweep, bool by_h) const;
  Curves adaptive_curves(bool max_error) const;
  plot::Panel max_error_panel() const;
  plot::Figure work_precision_figure() const;
  plot::Figure error_vs_step_figure(const json& orders) const;
  std::string scheme_name(const RunSpec& r) const {
    return r.adaptive() ? "adaptive " + variants_[r.variant].name : variants_[r.variant].name;
  }

  BenchOptions opt_;
  std::ostream& out_;
  YAML::Node doc_;
  std::string scene_name_;
  double h0_ = 0;
  std::vector<SchemeVariant> variants_;
  std::vector<std::string> variant_files_;
  std::vector<std::string> participants_, sampled_;
  std::map<std::pair<std::string, double>, std::unique_ptr<Reference>> refs_;
  std::uint64_t run_counter_ = 0;
  std::optional<std::string> best_scheme_;  // of the best-vs-zero-order-hold comparison
  // The adaptive points (RunSpec::tolerance > 0), loosest tolerance first per variant.
  std::vector<RunSpec> adaptive_specs_;
  std::vector<RunResult> adaptive_results_;
  double adaptive_max_ = 0, adaptive_min_ = 0, adaptive_initial_ = 0;  // time.max, time.min, time.initial of the adaptive runs
  // time.scales of the adaptive points per variant, and where they come from ("scene", or
  // "reference range" for a scene without them: reference_scales).
  std::map<int, std::vector<std::pair<std::string, double>>> adaptive_scales_;
  std::string adaptive_scales_from_ = "scene";
  std::vector<std::pair<std::string, double>> reference_scales(int variant, double h);
  // A scene with an adaptive step of its own: its settings (all but the tolerance, which is
  // swept) for the adaptive points; the fixed points sweep H around a tenth of its max.
  std::optional<config::AdaptiveStepSpec> scene_adaptive_;

  Clock::time_point t_start_;
  std::vector<std::string> refused_variants_;  // "name: why" of the variants the scene refuses
  // The fixed-H sweep: its grid, solvers and tolerances, and one spec and result per run.
  std::vector<double> grid_;
  std::vector<std::string> solvers_;
  std::vector<double> rtols_;
  std::vector<RunSpec> specs_;
  std::vector<RunResult> results_;
  std::vector<std::size_t> dds_specs_;  // the runs repeated through `mechsim launch`
  json dds_ = json::array();            // their outcomes
  std::vector<double> tolerances_;      // of the adaptive points
  json adaptive_choice_ = json::array();  // the variants with adaptive points, and why
};

// The node solvers' statistics of an in-process run, summed over the nodes.
json solver_totals(const cosim::InprocRunResult& ir);

}  // namespace mechsim::bench

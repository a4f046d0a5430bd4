#include "bench.h"

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
#include <sstream>

#include "bench_runner.h"
#include "elapsed.h"
#include "mechsim/config/units.h"
#include "mechsim/cosim/scene_plan.h"
#include "stdout_to_dev_null.h"

namespace mechsim::bench {

namespace fs = std::filesystem;

// The entries of a comma-separated list, trimmed, empty ones left out.
static std::vector<std::string> list_items(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto b = item.find_first_not_of(" \t"), e = item.find_last_not_of(" \t");
    if (b != std::string::npos) items.push_back(item.substr(b, e - b + 1));
  }
  return items;
}

std::vector<double> parse_steps(const std::string& text) {
  std::vector<double> out;
  for (const std::string& item : list_items(text)) {
    double v = 0;
    try {
      v = config::parse_quantity_as(item, config::dim::time);
    } catch (const std::exception& ex) {
      throw std::invalid_argument("--steps: '" + item + "': " + ex.what());
    }
    if (!(v > 0)) throw std::invalid_argument("--steps: '" + item + "': expected a positive time");
    out.push_back(v);
  }
  if (out.empty()) throw std::invalid_argument("--steps: expected a comma-separated list of times, e.g. '25 us,50 us'");
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<double> parse_tolerances(const std::string& text) {
  std::vector<double> out;
  for (const std::string& item : list_items(text)) {
    if (item == "none") continue;
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || !(v > 0) || !(v < 1))
      throw std::invalid_argument("--tolerances: expected numbers in (0, 1) or 'none', got '" + item + "'");
    out.push_back(v);
  }
  std::sort(out.begin(), out.end(), std::greater<>());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Loads and validates the scene as given (with overrides); nullptr after printing why.
std::unique_ptr<config::Scene> Bench::load_base_scene() const {
  std::unique_ptr<config::Scene> base;
  try {
    base = std::make_unique<config::Scene>(config::load_scene(opt_.scene_path, opt_.overrides));
    cosim::ScenePlan::build(*base);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return nullptr;
  }
  if (base->compare.empty()) {
    std::fprintf(stderr, "mechsim bench: %s: the scene has no 'compare:' outputs to measure the error on\n",
                 opt_.scene_path.c_str());
    return nullptr;
  }
  return base;
}

// The scene's name, step, document and participants, and the work folder. False when no
// work folder can be made.
bool Bench::take_scene(const config::Scene& base) {
  scene_name_ = base.name;
  h0_ = base.time.step;
  doc_ = YAML::Clone(base.root.yaml());
  if (base.time.adaptive) {
    // The fixed points need a fixed step: the scene's time section without its adaptive
    // keys, H around a tenth of its max (the adaptive points keep the scene's settings).
    scene_adaptive_ = base.time.adaptive;
    const double span = base.time.end - base.time.start;
    h0_ = span / std::max(1.0, std::round(span / (scene_adaptive_->max / 10)));  // a whole number of steps
    for (const char* key : {"tolerance", "min", "max", "initial", "scales"}) doc_["time"].remove(key);
    doc_["time"]["step"] = time_text(h0_);
  }
  for (const auto& p : base.participants) {
    participants_.push_back(p.name);
    if (doc_["participants"][p.name]["params"] && doc_["participants"][p.name]["params"]["sample_time"])
      sampled_.push_back(p.name);
  }
  if (opt_.work_dir.empty()) {
    char tmpl[] = "/tmp/mechsim-bench-XXXXXX";
    if (!mkdtemp(tmpl)) {
      std::perror("mechsim bench: mkdtemp");
      return false;
    }
    opt_.work_dir = tmpl;
  } else {
    fs::create_directories(opt_.work_dir);
  }
  return true;
}

// Scheme variants valid for this scene (checked by the scene validator at the scene's H),
// each written to a scene file of its own. False (after saying why) when none is left.
bool Bench::choose_variants() {
  for (auto& v : scheme_variants(doc_)) {
    if (!opt_.schemes.empty() && std::find(opt_.schemes.begin(), opt_.schemes.end(), v.name) == opt_.schemes.end())
      continue;
    if (opt_.schemes.empty() && opt_.quick && !(v.shipped || v.zero_order_hold_jacobi || v.name == "jacobi/linear" ||
                                                v.name == "compliant/linear" || v.name == "interface_jacobian/10" ||
                                                v.shipped_quadratic))
      continue;
    const std::string file = opt_.work_dir + "/" + scene_name_ + "." + std::to_string(variants_.size()) + ".yaml";
    {
      YAML::Emitter em;
      em << v.document;
      std::ofstream(file) << "# mechsim bench: " << opt_.scene_path << " with scheme " << v.name << "\n" << em.c_str() << "\n";
    }
    try {
      config::Scene s = config::load_scene(file, opt_.overrides);
      cosim::ScenePlan::build(s);
    } catch (const std::exception& e) {
      refused_variants_.push_back(v.name + ": " + e.what());
      continue;
    }
    variants_.push_back(v);
    variant_files_.push_back(file);
  }
  // The shipped connections are often one of the variants (nc_slide_loop_1ms ships
  // interface_jacobian/10): run them once, under the variant's name, marked shipped.
  if (!variants_.empty() && variants_[0].shipped) {
    for (std::size_t i = 1; i < variants_.size(); ++i) {
      if (same_yaml(variants_[i].document["connections"], variants_[0].document["connections"])) {
        variants_[i].shipped = true;
        variants_.erase(variants_.begin());
        variant_files_.erase(variant_files_.begin());
        break;
      }
    }
  }
  if (variants_.empty()) {
    std::fprintf(stderr, "mechsim bench: no coupling scheme to sweep%s\n",
                 opt_.schemes.empty() ? " (the scene has no connections)" : " (--schemes matches none valid here)");
    for (const auto& r : refused_variants_) std::fprintf(stderr, "  refused %s\n", r.c_str());
    return false;
  }
  return true;
}

// The fixed-H runs: every variant at every usable H with every solver, and the tolerance
// sweep with cvode_bdf. False (after saying why) when no H divides the run.
bool Bench::plan_sweep(const config::Scene& base) {
  std::vector<double> steps = opt_.steps;
  if (steps.empty()) {
    const std::vector<double> factors = opt_.quick ? std::vector<double>{1, 2, 4} : std::vector<double>{0.25, 0.5, 1, 2, 4, 10};
    for (double f : factors) steps.push_back(h0_ * f);
  }
  // Only steps that divide the run into whole macro steps.
  for (double h : steps) {
    const double n = (base.time.end - base.time.start) / h;
    if (std::abs(n - std::round(n)) > 1e-6 * n || n < 4) {
      std::fprintf(stderr, "mechsim bench: skipping H = %s: not a whole number of steps over the run\n", time_text(h).c_str());
      continue;
    }
    grid_.push_back(h);
  }
  if (grid_.empty()) {
    std::fprintf(stderr, "mechsim bench: no usable macro step\n");
    return false;
  }
  solvers_ = opt_.solvers;
  if (solvers_.empty())
    solvers_ = opt_.quick ? std::vector<std::string>{"cvode_bdf"}
                          : std::vector<std::string>{"cvode_bdf", "cvode_adams", "arkode_erk", "arkode_dirk"};
  rtols_ = opt_.rtols;
  if (rtols_.empty()) rtols_ = opt_.quick ? std::vector<double>{1e-8} : std::vector<double>{1e-4, 1e-8};

  for (int v = 0; v < static_cast<int>(variants_.size()); ++v)
    for (double h : grid_) {
      for (const auto& s : solvers_) specs_.push_back({v, h, s, opt_.rtol, "solver"});
      for (double rt : rtols_)
        if (rt != opt_.rtol) specs_.push_back({v, h, "cvode_bdf", rt, "tolerance"});
    }

  std::fprintf(stderr, "mechsim bench: %s: %zu schemes x %zu steps (%s .. %s) x %zu solvers + %zu tolerances = %zu runs in process\n",
               scene_name_.c_str(), variants_.size(), grid_.size(), time_text(grid_.front()).c_str(),
               time_text(grid_.back()).c_str(), solvers_.size(), rtols_.size(), specs_.size());
  for (const auto& r : refused_variants_) std::fprintf(stderr, "  scheme refused by the scene: %s\n", r.c_str());
  return true;
}

// DDS spot checks: the shipped scheme at the scene's H, then the zero-order-hold baseline.
void Bench::choose_dds_checks() {
  int n_dds = opt_.dds_checks >= 0 ? opt_.dds_checks : (opt_.quick ? 1 : 2);
  for (int pass = 0; pass < 2 && static_cast<int>(dds_specs_.size()) < n_dds; ++pass)
    for (std::size_t i = 0; i < specs_.size(); ++i) {
      const auto& v = variants_[specs_[i].variant];
      if (specs_[i].sweep == "solver" && specs_[i].solver == solvers_.front() &&
          (pass == 0 ? v.shipped && std::abs(specs_[i].h - h0_) < 1e-12 * h0_
                     : v.zero_order_hold_jacobi && specs_[i].h == grid_.front())) {
        dds_specs_.push_back(i);
        break;
      }
    }
  if (static_cast<int>(dds_specs_.size()) > n_dds) dds_specs_.resize(n_dds);
}

// Every fixed-H run in process, with its DDS spot check where one was chosen.
void Bench::run_sweep() {
  results_.resize(specs_.size());
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    const RunSpec& r = specs_[i];
    const std::string dir = opt_.work_dir + "/inproc-" + std::to_string(i);
    const bool keep = std::find(dds_specs_.begin(), dds_specs_.end(), i) != dds_specs_.end();
    results_[i] = run_inproc_point(r, dir);
    const RunResult& res = results_[i];
    std::fprintf(stderr, "[%zu/%zu %5.0f s] %-22s H %-9s %-11s rtol %-6s %-8s rms %-10s wall %s s\n", i + 1, specs_.size(),
                 seconds_since(t_start_), variants_[r.variant].name.c_str(), time_text(r.h).c_str(), r.solver.c_str(),
                 num(r.rtol, "%.0e").c_str(), res.status.c_str(),
                 res.rms_below_reference ? "<ref" : num(res.rms_rel).c_str(), num(res.wall_time_s).c_str());
    if (keep) {
      std::fprintf(stderr, "  DDS spot check: mechsim launch, %s at H %s ...\n", variants_[r.variant].name.c_str(),
                   time_text(r.h).c_str());
      json d = dds_check(r, res);
      std::fprintf(stderr, "  DDS spot check: %s, outputs %s the in-process run's\n", d.value("status", "?").c_str(),
                   d.value("outputs_identical", false) ? "bit-identical to" : "DIFFERENT from");
      dds_.push_back(d);
    }
    if (!opt_.keep_work_dir) {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  }
}

// The bench in the order it runs: the scene, the variants and the grid; the fixed-H runs
// (with the DDS spot checks), the adaptive points; the figures drawn from them; the table,
// the plots and the JSON.
int Bench::run() {
  t_start_ = Clock::now();
  const std::unique_ptr<config::Scene> base = load_base_scene();
  if (!base) return 2;
  if (!take_scene(*base)) return 1;
  if (!choose_variants() || !plan_sweep(*base)) return 2;
  choose_dds_checks();
  json orders, ten_x, adaptive_vs_fixed_json;
  {
    const tools::StdoutToDevNull quiet_nodes;
    run_sweep();
    choose_adaptive_points();
    run_adaptive_points();
    orders = observed_orders();
    ten_x = best_vs_zero_order_hold();
    adaptive_vs_fixed_json = adaptive_vs_fixed();
  }
  const double duration = seconds_since(t_start_);
  print_rows();
  print_findings(orders, ten_x);
  print_adaptive_vs_fixed(adaptive_vs_fixed_json);
  out_ << "bench duration " << num(duration, "%.1f") << " s\n";
  plots(orders);
  if (!opt_.json_path.empty()) write_json(orders, ten_x, adaptive_vs_fixed_json, duration);
  if (!opt_.keep_work_dir) {
    std::error_code ec;
    fs::remove_all(opt_.work_dir, ec);
  }
  return 0;
}

int run_bench(const BenchOptions& options, std::ostream& out) {
  Bench b(options, out);
  return b.run();
}

}  // namespace mechsim::bench

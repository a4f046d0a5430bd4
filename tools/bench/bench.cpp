#include "bench.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "json_io.h"
#include "mechsim/config/scene.h"
#include "mechsim/config/units.h"
#include "mechsim/cosim/composer.h"
#include "mechsim/cosim/inproc_run.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/scene_plan.h"
#include "plot.h"
#include "provenance.h"
#include "reference_accuracy.h"
#include "run_report.h"
#include "signal_compare.h"
#include "elapsed.h"

namespace mechsim::bench {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();


// "250 us", "1 ms", "2.5 ms": exact enough for the scene grammar (9 significant digits).
std::string time_text(double s) {
  char buf[64];
  if (s < 1e-3)
    std::snprintf(buf, sizeof buf, "%.9g us", s * 1e6);
  else if (s < 1.0)
    std::snprintf(buf, sizeof buf, "%.9g ms", s * 1e3);
  else
    std::snprintf(buf, sizeof buf, "%.9g s", s);
  return buf;
}

std::string num(double v, const char* fmt = "%.3g") {
  if (!std::isfinite(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// A tolerance as "1e-3", "2.5e-4".
std::string tol_text(double v) {
  if (!std::isfinite(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2e", v);
  std::string m(buf), e;
  const auto pos = m.find('e');
  if (pos != std::string::npos) {
    e = m.substr(pos + 1);
    m.resize(pos);
  }
  while (m.find('.') != std::string::npos && (m.back() == '0' || m.back() == '.')) m.pop_back();
  std::string sign;
  if (!e.empty() && (e[0] == '-' || e[0] == '+')) {
    if (e[0] == '-') sign = "-";
    e = e.substr(1);
  }
  while (e.size() > 1 && e[0] == '0') e = e.substr(1);
  return e == "0" ? m : m + "e" + sign + e;
}

json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// --- scheme variants ---------------------------------------------------------------

YAML::Node connection(const std::string& from, const std::string& to) {
  YAML::Node c(YAML::NodeType::Map);
  c["from"] = from;
  c["to"] = to;
  return c;
}

// Equal as data (flow or block style, key order aside): scalars by their text.
bool same_yaml(const YAML::Node& a, const YAML::Node& b) {
  if (a.Type() != b.Type()) return false;
  if (a.IsScalar()) return a.Scalar() == b.Scalar();
  if (a.IsSequence()) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!same_yaml(a[i], b[i])) return false;
    return true;
  }
  if (a.IsMap()) {
    if (a.size() != b.size()) return false;
    for (const auto& kv : a) {
      const YAML::Node other = b[kv.first.Scalar()];
      if (!other || !same_yaml(kv.second, other)) return false;
    }
    return true;
  }
  return true;  // both null
}

}  // namespace

std::vector<SchemeVariant> scheme_variants(const YAML::Node& scene_document) {
  std::vector<SchemeVariant> out;
  const YAML::Node conns = scene_document["connections"];
  if (!conns || !conns.IsSequence() || conns.size() == 0) return out;

  // The connection that crosses a coupling element (at most one is handled: the shipped
  // scenes have one), and its reverse direction if the scene lists it.
  int cut = -1, reverse = -1;
  for (std::size_t i = 0; i < conns.size(); ++i)
    if (conns[i]["coupling"]) cut = static_cast<int>(i);
  auto s = [](const YAML::Node& n, const char* key, const std::string& def = "") {
    return n[key] ? n[key].as<std::string>() : def;
  };
  auto clone = [&] { return YAML::Clone(scene_document); };
  // The scene as shipped.
  {
    SchemeVariant v;
    v.name = "shipped";
    v.family = "shipped";
    v.shipped = true;
    v.document = clone();
    out.push_back(v);
  }
  // The scene's own orders with every Jacobi edge extrapolated quadratically: under an
  // error-controlled step the predictor's order buys longer steps (docs/accuracy.md, "The
  // predictor's order and the node solvers' floor"), where at a fixed H the scene's lower
  // order may be the better one. Left out where it changes nothing; where another variant
  // has the same connections, that one is marked instead (below).
  std::optional<YAML::Node> quadratic_connections;
  {
    YAML::Node doc = clone();
    bool changed = false;
    for (auto c : doc["connections"]) {
      const bool jacobi = s(c, "order", "jacobi") == "jacobi";
      const YAML::Node& edge = c;  // const: operator[] must not add keys
      const bool interface_jacobian = edge["coupling"] && s(edge["coupling"], "scheme") == "interface_jacobian";
      if (!jacobi || interface_jacobian || s(c, "reconstruction", "hold") == "quadratic") continue;
      c["reconstruction"] = "quadratic";
      changed = true;
    }
    if (changed) quadratic_connections = doc["connections"];
  }
  // Appends the quadratic variant of the shipped orders, or marks its twin among `out`.
  const auto add_shipped_quadratic = [&] {
    if (!quadratic_connections) return;
    for (auto& v : out)
      if (same_yaml(v.document["connections"], *quadratic_connections)) {
        v.shipped_quadratic = true;
        return;
      }
    SchemeVariant v;
    v.name = "shipped/quadratic";
    v.family = "shipped";
    v.shipped_quadratic = true;
    v.document = clone();
    v.document["connections"] = *quadratic_connections;
    out.push_back(v);
  };

  if (cut >= 0) {
    const std::string a = s(conns[cut], "from"), b = s(conns[cut], "to");
    for (std::size_t i = 0; i < conns.size(); ++i)
      if (s(conns[i], "from") == b && s(conns[i], "to") == a) reverse = static_cast<int>(i);
    YAML::Node element = YAML::Clone(conns[cut]["coupling"]);
    // The cut rewritten; every other connection as shipped.
    auto with_cut = [&](const std::vector<YAML::Node>& cut_connections) {
      YAML::Node doc = clone();
      YAML::Node list(YAML::NodeType::Sequence);
      for (std::size_t i = 0; i < conns.size(); ++i) {
        if (static_cast<int>(i) == cut) {
          for (const auto& c : cut_connections) list.push_back(c);
        } else if (static_cast<int>(i) != reverse) {
          list.push_back(YAML::Clone(conns[i]));
        }
      }
      doc["connections"] = list;
      return doc;
    };
    for (const char* rec : {"hold", "linear", "quadratic"}) {
      YAML::Node e = YAML::Clone(element);
      e["scheme"] = "compliant";
      e.remove("levels");
      YAML::Node fwd = connection(a, b), back = connection(b, a);
      fwd["order"] = "jacobi";
      fwd["reconstruction"] = rec;
      fwd["coupling"] = e;
      back["order"] = "jacobi";
      back["reconstruction"] = rec;
      SchemeVariant v;
      v.name = std::string("compliant/") + rec;
      v.family = "compliant";
      v.zero_order_hold_jacobi = std::string(rec) == "hold";
      v.document = with_cut({fwd, back});
      out.push_back(v);
    }
    for (int levels : {1, 2, 10}) {
      YAML::Node e = YAML::Clone(element);
      e["scheme"] = "interface_jacobian";
      e["levels"] = levels;
      YAML::Node fwd = connection(a, b);
      fwd["coupling"] = e;
      SchemeVariant v;
      v.name = "interface_jacobian/" + std::to_string(levels);
      v.family = "interface_jacobian";
      v.document = with_cut({fwd});
      out.push_back(v);
    }
    add_shipped_quadratic();
    return out;
  }

  // No coupling element: the order and reconstruction of every connection.
  bool has_gs = false;
  for (const auto& c : conns) has_gs = has_gs || s(c, "order", "jacobi") == "gauss_seidel";
  // One variant per reconstruction: the connections `first(c, i, n)` picks become
  // Gauss-Seidel edges, every other one a Jacobi edge reconstructed with `rec`.
  const auto ordered = [&](const std::string& family, const auto& first) {
    for (const char* rec : {"hold", "linear", "quadratic"}) {
      YAML::Node doc = clone();
      std::size_t i = 0;
      const std::size_t n = doc["connections"].size();
      for (auto c : doc["connections"]) {
        const bool gs = first(c, i, n);
        ++i;
        if (gs) {
          c["order"] = "gauss_seidel";
          c.remove("reconstruction");
          c.remove("initial");  // a Gauss-Seidel edge waits for the partner's step-0 sample
        } else {
          c["order"] = "jacobi";
          c["reconstruction"] = rec;
        }
      }
      SchemeVariant v;
      v.name = family + "/" + rec;
      v.family = family;
      v.zero_order_hold_jacobi = family == "jacobi" && std::string(rec) == "hold";
      v.document = doc;
      out.push_back(v);
    }
  };
  ordered("jacobi", [](const YAML::Node&, std::size_t, std::size_t) { return false; });
  // The scene's Gauss-Seidel edges (or, without any, its first connection) first.
  ordered("gauss_seidel", [&](const YAML::Node& c, std::size_t i, std::size_t) {
    return has_gs ? s(c, "order", "jacobi") == "gauss_seidel" : i == 0;
  });
  // The other ordering: the edges that were Jacobi go first (Gauss-Seidel) and the
  // Gauss-Seidel ones become Jacobi (without any Gauss-Seidel edge: the last connection
  // first). The validator refuses an ordering with a Gauss-Seidel cycle.
  ordered("gauss_seidel_reversed", [&](const YAML::Node& c, std::size_t i, std::size_t n) {
    return has_gs ? s(c, "order", "jacobi") != "gauss_seidel" : i + 1 == n;
  });
  add_shipped_quadratic();
  return out;
}

double fit_order(const std::vector<double>& h, const std::vector<double>& error) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < h.size() && i < error.size(); ++i) {
    if (!(error[i] > 0) || !std::isfinite(error[i]) || !(h[i] > 0)) continue;
    const double x = std::log(h[i]), y = std::log(error[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++n;
  }
  if (n < 3) return kNaN;
  const double d = n * sxx - sx * sx;
  return d > 0 ? (n * sxy - sx * sy) / d : kNaN;
}

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

double envelope_at(const std::vector<std::pair<double, double>>& points, double wall, int* lo, int* hi) {
  std::vector<int> idx;
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    const auto& [w, e] = points[i];
    if (w > 0 && std::isfinite(w) && e > 0 && std::isfinite(e)) idx.push_back(i);
  }
  if (lo) *lo = -1;
  if (hi) *hi = -1;
  if (idx.empty() || !(wall > 0)) return kNaN;
  std::sort(idx.begin(), idx.end(), [&](int a, int b) {
    return points[a].first != points[b].first ? points[a].first < points[b].first : points[a].second < points[b].second;
  });
  if (wall < points[idx.front()].first || wall > points[idx.back()].first) return kNaN;
  // The corners: each point with a smaller error than every faster one.
  std::vector<int> corners;
  for (int i : idx)
    if (corners.empty() || points[i].second < points[corners.back()].second) corners.push_back(i);
  std::size_t k = 0;
  while (k + 1 < corners.size() && points[corners[k + 1]].first <= wall) ++k;
  const int a = corners[k];
  if (k + 1 == corners.size() || points[a].first == wall) {
    if (lo) *lo = a;
    if (hi) *hi = a;
    return points[a].second;
  }
  const int b = corners[k + 1];
  const double x0 = std::log(points[a].first), x1 = std::log(points[b].first);
  const double y0 = std::log(points[a].second), y1 = std::log(points[b].second);
  if (lo) *lo = a;
  if (hi) *hi = b;
  return std::exp(y0 + (y1 - y0) * (std::log(wall) - x0) / (x1 - x0));
}

namespace {

// --- one bench -----------------------------------------------------------------------

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
  void compare(const config::Scene& scene, const Reference& ref, const std::vector<std::string>& participants,
               const std::function<std::string(const std::string&)>& log_path, RunResult& res);
  json dds_check(const RunSpec& r, const RunResult& inproc);
  json row_json(const RunSpec& r, const RunResult& res) const;
  void plots(const std::vector<RunSpec>& specs, const std::vector<RunResult>& results, const json& orders);
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
    slot->accuracy_json = launch::reference_accuracy_json(*slot->scene, slot->run, slot->accuracy);
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
    ref.accuracy_json = launch::reference_accuracy_json(*ref.scene, ref.run, ref.accuracy);
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
    const launch::SignalError e = launch::compare_signal(t, c, r);
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
  const launch::SeriesLookup reference_lookup = [&](const config::SignalRef& r) -> std::span<const double> {
    const int c = ref.run.log.column(r.full_name());
    return c < 0 ? std::span<const double>{} : std::span<const double>(ref.run.log.data[c]);
  };
  try {
    res.report = launch::report_figures(scene, t, cosim_series, &reference_lookup);
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
  res.wall_time_s = seconds_since(t0);
  // Short runs are timed again (the outputs are the same bit for bit) and the fastest is
  // kept: thread start and scheduling noise are a large part of a 50 ms run. Up to ten
  // runs, until half a second has gone by; and every run at least --repeat times (runs of
  // a second scatter by some 20 % on a shared machine).
  double timed = res.wall_time_s;
  for (int repeat = 1; repeat < std::max(10, opt_.repeat) && ir.ok &&
                       (repeat < opt_.repeat || (res.wall_time_s < 0.25 && timed < 0.5));
       ++repeat) {
    io.run_id = ++run_counter_;
    const auto t1 = Clock::now();
    const cosim::InprocRunResult again = cosim::run_inproc(*scene, io);
    const double wall = seconds_since(t1);
    timed += wall;
    if (again.ok) res.wall_time_s = std::min(res.wall_time_s, wall);
  }
  long steps = 0, rhs = 0, etf = 0, nlf = 0, roots = 0;
  for (const auto& n : ir.nodes) {
    steps += n.last.solver_steps;
    rhs += n.last.rhs_evals;
    etf += n.last.error_test_failures;
    nlf += n.last.nonlinear_failures;
    roots += n.last.roots_found;
  }
  res.solver = {{"steps", steps}, {"rhs_evals", rhs}, {"error_test_failures", etf}, {"nonlinear_failures", nlf},
                {"roots_found", roots}};
  if (r.adaptive()) {
    // The macro steps it took: the rows of a node's log after the first.
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

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

bool same_bytes(const std::string& a, const std::string& b) {
  std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
  if (!fa || !fb) return false;
  std::string sa((std::istreambuf_iterator<char>(fa)), {}), sb((std::istreambuf_iterator<char>(fb)), {});
  return sa == sb;
}

// The same run as real node processes through `mechsim launch`, its error as the launcher
// reports it, and whether every node's output log equals the in-process run's byte for byte.
json Bench::dds_check(const RunSpec& r, const RunResult& inproc) {
  std::string exe = opt_.mechsim_exe.empty() ? fs::read_symlink("/proc/self/exe").string() : opt_.mechsim_exe;
  // A rebuilt executable while the bench runs: the link names the old, deleted file.
  const std::string deleted = " (deleted)";
  if (exe.size() > deleted.size() && exe.compare(exe.size() - deleted.size(), deleted.size(), deleted) == 0)
    exe.resize(exe.size() - deleted.size());
  const std::string dir = opt_.work_dir + "/dds-" + std::to_string(++run_counter_);
  fs::create_directories(dir);
  std::string cmd = shell_quote(exe) + " launch " + shell_quote(variant_files_[r.variant]);
  for (const auto& o : run_overrides(r, true)) cmd += " --set " + shell_quote(o);
  cmd += " --json " + shell_quote(dir + "/summary.json") + " --runs-dir " + shell_quote(dir) + " --no-plot --no-progress";
  cmd += " >" + shell_quote(dir + "/launch.log") + " 2>&1";
  const auto t0 = Clock::now();
  const int rc = std::system(cmd.c_str());
  const double elapsed = seconds_since(t0);
  json out{{"scheme", variants_[r.variant].name}, {"step_s", r.h}, {"solver", r.solver}, {"rtol", r.rtol},
           {"launch_exit", WIFEXITED(rc) ? WEXITSTATUS(rc) : -1}, {"process_time_s", elapsed}};
  json summary;
  try {
    std::ifstream f(dir + "/summary.json");
    summary = json::parse(f);
  } catch (const std::exception& e) {
    out["status"] = "failed";
    out["reason"] = "no summary from mechsim launch (see " + dir + "/launch.log)";
    return out;
  }
  out["status"] = summary.value("status", "?");
  out["wall_time_s"] = summary.value("wall_time_s", kNaN);
  out["inproc_wall_time_s"] = finite_or_null(inproc.wall_time_s);
  const std::string run_dir = summary.value("run_dir", "");
  // Equal outcomes: both ran through, or both stopped (the launcher reports "failed" for a
  // diverged node); and the node logs equal byte for byte up to where they stopped.
  out["inproc_status"] = inproc.status;
  const bool dds_ok = out["status"] == "ok", inproc_ok = inproc.completed;
  bool identical = !run_dir.empty() && dds_ok == inproc_ok;
  json nodes = json::object();
  for (const auto& p : participants_) {
    const bool same = same_bytes(inproc.run_dir + "/" + p + ".outputs.bin", run_dir + "/" + p + ".outputs.bin");
    nodes[p] = same;
    identical = identical && same;
  }
  out["outputs_identical"] = identical;
  out["nodes_identical"] = nodes;
  // The launcher's figures next to the bench's (the same code computes both).
  json diff = json::object();
  double worst = 0;
  if (summary.contains("signals"))
    for (auto& [name, s] : summary["signals"].items()) {
      if (!inproc.signals.contains(name) || !inproc.signals[name].contains("rms_abs_error")) continue;
      const json& b = inproc.signals[name]["rms_abs_error"];
      const double dds_rms = s.value("rms_abs_error", kNaN);
      if (b.is_number()) {
        const double d = std::abs(dds_rms - b.get<double>());
        worst = std::max(worst, std::isfinite(d) ? d : std::numeric_limits<double>::infinity());
      }
      diff[name] = {{"dds_rms_abs_error", finite_or_null(dds_rms)}, {"inproc_rms_abs_error", b}};
    }
  out["signals"] = diff;
  out["max_rms_abs_difference"] = finite_or_null(worst);
  out["run_dir"] = run_dir;
  return out;
}

json Bench::row_json(const RunSpec& r, const RunResult& res) const {
  const auto& v = variants_[r.variant];
  json row = {{"scheme", scheme_name(r)},
          {"family", v.family},
          {"zero_order_hold_jacobi", v.zero_order_hold_jacobi},
          {"shipped", v.shipped},
          {"step_s", r.adaptive() ? json(nullptr) : json(r.h)},
          {"solver", r.solver},
          {"rtol", r.rtol},
          {"atol", r.rtol * 1e-3},
          {"sweep", r.sweep},
          {"transport", "inproc"},
          {"status", res.status},
          {"reason", res.reason},
          {"wall_time_s", finite_or_null(res.wall_time_s)},
          {"macro_steps", res.macro_steps},
          {"solver_stats", res.solver},
          {"error",
           {{"signal", res.worst_signal},
            {"rms_rel", finite_or_null(res.rms_rel)},
            {"max_rel", finite_or_null(res.max_rel)},
            {"rms_below_reference_accuracy", res.rms_below_reference},
            {"max_below_reference_accuracy", res.max_below_reference},
            {"rms_rel_bound", finite_or_null(res.rms_rel_bound)}}},
          {"signals", res.signals},
          {"report", res.report}};
  if (r.adaptive()) {
    row["variant"] = v.name;
    row["tolerance"] = r.tolerance;
    row["time_max_s"] = adaptive_max_;
    row["time_min_s"] = adaptive_min_;
    row["time_initial_s"] = adaptive_initial_;
    row["scales"] = json::object();
    if (const auto it = adaptive_scales_.find(r.variant); it != adaptive_scales_.end())
      for (const auto& [field, scale] : it->second) row["scales"][field] = scale;
    row["scales_from"] = adaptive_scales_from_;
    row["steps_taken_s"] = {{"min", finite_or_null(res.step_min_s)}, {"max", finite_or_null(res.step_max_s)}};
    row["reference"] = res.reference;
  }
  return row;
}

void Bench::plots(const std::vector<RunSpec>& specs, const std::vector<RunResult>& results, const json& orders) {
  if (opt_.plots_dir.empty()) return;
  fs::create_directories(opt_.plots_dir);
  // Curves: (scheme, solver[, rtol]) -> points sorted by H.
  auto curves = [&](const std::string& sweep, bool by_h) {
    std::map<std::string, std::vector<std::pair<double, double>>> c;
    std::map<std::string, std::map<double, double>> yv;
    for (std::size_t i = 0; i < specs.size(); ++i) {
      if (specs[i].sweep != sweep && !(sweep == "tolerance" && specs[i].solver == "cvode_bdf")) continue;
      const auto& res = results[i];
      if (res.status != "ok" || !std::isfinite(res.rms_rel)) continue;
      std::string name = variants_[specs[i].variant].name + " " + specs[i].solver;
      if (sweep == "tolerance") name = variants_[specs[i].variant].name + " rtol " + num(specs[i].rtol, "%.0e");
      c[name].push_back({specs[i].h, res.wall_time_s});
      yv[name][specs[i].h] = res.rms_rel;
    }
    // Along a curve the points follow H (sorted), whatever the wall time does.
    std::map<std::string, std::vector<std::pair<double, double>>> out;
    for (auto& [k, pts] : c) {
      std::sort(pts.begin(), pts.end());
      for (const auto& [h, wall] : pts) out[k].push_back({by_h ? h : wall, yv[k][h]});
    }
    return out;
  };
  auto panel_of = [&](const std::map<std::string, std::vector<std::pair<double, double>>>& c, const std::string& title,
                      const std::string& xlabel) {
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
  };
  // The adaptive curves (cvode_bdf at --rtol): points along a curve are tolerances, loosest
  // first; RMS or max error of the worst compared signal.
  auto adaptive_curves = [&](bool max_error) {
    std::map<std::string, std::vector<std::pair<double, double>>> c;
    for (std::size_t i = 0; i < adaptive_specs_.size(); ++i) {
      const auto& res = adaptive_results_[i];
      const double e = max_error ? res.max_rel : res.rms_rel;
      if (res.status != "ok" || !std::isfinite(e)) continue;
      c[scheme_name(adaptive_specs_[i])].push_back({res.wall_time_s, e});
    }
    return c;
  };
  const bool any_adaptive = !adaptive_curves(false).empty() || !adaptive_curves(true).empty();
  plot::Figure wp;
  wp.title = scene_name_ + (any_adaptive ? ": work-precision (in process; points along a curve: H, adaptive: tolerances)"
                                          : ": work-precision (in-process runs; points along a curve are macro steps H)");
  wp.height_px_per_panel = 420;
  // One panel per node solver (a curve per scheme), then the tolerance sweep.
  const auto all = curves("solver", false);
  std::vector<std::string> solver_names;
  for (const auto& sp : specs)
    if (sp.sweep == "solver" && std::find(solver_names.begin(), solver_names.end(), sp.solver) == solver_names.end())
      solver_names.push_back(sp.solver);
  for (const auto& solver : solver_names) {
    std::map<std::string, std::vector<std::pair<double, double>>> sub;
    const std::string suffix = " " + solver;
    for (const auto& [name, pts] : all)
      if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
        sub[name.substr(0, name.size() - suffix.size())] = pts;
    if (solver == "cvode_bdf")
      for (const auto& [name, pts] : adaptive_curves(false)) sub[name] = pts;
    wp.panels.push_back(panel_of(sub, solver + " in every node (rtol " + num(opt_.rtol, "%.0e") + ")", "wall time [s]"));
  }
  // The max error (the 5x target of the adaptive step): fixed-H schemes and adaptive curves,
  // cvode_bdf at --rtol.
  if (any_adaptive) {
    std::map<std::string, std::map<double, std::pair<double, double>>> fixed;  // scheme -> H -> (wall, max)
    for (std::size_t i = 0; i < specs.size(); ++i) {
      const auto& res = results[i];
      if (specs[i].sweep != "solver" || specs[i].solver != "cvode_bdf" || specs[i].rtol != opt_.rtol) continue;
      if (res.status != "ok" || !std::isfinite(res.max_rel)) continue;
      fixed[variants_[specs[i].variant].name][specs[i].h] = {res.wall_time_s, res.max_rel};
    }
    std::map<std::string, std::vector<std::pair<double, double>>> sub;
    for (const auto& [name, by_h] : fixed)
      for (const auto& [h, p] : by_h) sub[name].push_back(p);
    for (const auto& [name, pts] : adaptive_curves(true)) sub[name] = pts;
    plot::Panel p = panel_of(sub, "max error: fixed H and adaptive (cvode_bdf, rtol " + num(opt_.rtol, "%.0e") + ")", "wall time [s]");
    p.ylabel = "max error / reference range (worst compared signal)";
    wp.panels.push_back(p);
  }
  // The tolerance panel keeps the baseline, the shipped scheme and the best one readable.
  auto tol = curves("tolerance", false);
  {
    std::set<std::string> keep;
    for (const auto& v : variants_)
      if (v.zero_order_hold_jacobi || v.shipped) keep.insert(v.name);
    if (best_scheme_) keep.insert(*best_scheme_);
    for (auto it = tol.begin(); it != tol.end();) {
      const std::string scheme = it->first.substr(0, it->first.find(" rtol "));
      it = keep.count(scheme) ? std::next(it) : tol.erase(it);
    }
  }
  if (!tol.empty()) wp.panels.push_back(panel_of(tol, "tolerance sweep (cvode_bdf; baseline, shipped and best scheme)", "wall time [s]"));
  std::string why;
  const std::string wp_path = opt_.plots_dir + "/" + scene_name_ + "_work_precision.png";
  if (!plot::write_png(wp, wp_path, &why)) std::fprintf(stderr, "mechsim bench: no plot %s: %s\n", wp_path.c_str(), why.c_str());

  plot::Figure ord;
  ord.title = scene_name_ + ": error against macro step (cvode_bdf)";
  ord.height_px_per_panel = 520;
  auto by_h = curves("solver", true);
  std::map<std::string, std::vector<std::pair<double, double>>> bdf;
  for (auto& [name, pts] : by_h)
    if (name.size() > 10 && name.substr(name.size() - 10) == " cvode_bdf") {
      std::string label = name.substr(0, name.size() - 10);
      for (const auto& o : orders)
        if (o["scheme"] == label && o["order"].is_number()) label += " (order " + num(o["order"].get<double>(), "%.2f") + ")";
      bdf[label] = pts;
    }
  ord.panels.push_back(panel_of(bdf, "observed order: slope of log error against log H", "macro step H [s]"));
  const std::string ord_path = opt_.plots_dir + "/" + scene_name_ + "_error_vs_step.png";
  if (!plot::write_png(ord, ord_path, &why)) std::fprintf(stderr, "mechsim bench: no plot %s: %s\n", ord_path.c_str(), why.c_str());
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

// The tightest node tolerance swept (the observed orders are fitted there).
double Bench::tightest_rtol() const {
  double tight = opt_.rtol;
  for (double rt : rtols_) tight = std::min(tight, rt);
  return tight;
}

// Observed order per scheme: cvode_bdf at the tightest tolerance swept, over the points
// that are neither saturated by the tolerance/reference floor nor outside the asymptotic
// range (docs/accuracy.md).
json Bench::observed_orders() {
  json orders = json::array();
  const double tight = tightest_rtol();
  for (int v = 0; v < static_cast<int>(variants_.size()); ++v) {
    std::vector<double> hs, es;
    json used = json::array();
    for (std::size_t i = 0; i < specs_.size(); ++i) {
      const auto& r = specs_[i];
      if (r.variant != v || r.solver != "cvode_bdf" || r.rtol != tight) continue;
      const auto& res = results_[i];
      if (res.status != "ok" || !std::isfinite(res.rms_rel)) continue;
      double floor_rel = 0;
      const Reference& ref = reference(v, r.h);
      for (auto& [name, e] : ref.accuracy_json["signals"].items())
        floor_rel = std::max(floor_rel, e.value("rms_rel_difference", 0.0));
      floor_rel = std::max(floor_rel, r.rtol);
      if (res.rms_rel < 10 * floor_rel || res.rms_rel > 0.1) continue;
      hs.push_back(r.h);
      es.push_back(res.rms_rel);
      used.push_back(r.h);
    }
    const double p = fit_order(hs, es);
    orders.push_back({{"scheme", variants_[v].name},
                      {"solver", "cvode_bdf"},
                      {"rtol", tight},
                      {"order", finite_or_null(p)},
                      {"steps_used_s", used},
                      {"note", std::isfinite(p) ? "" : "fewer than 3 non-saturated stable points"}});
  }
  return orders;
}

// Best scheme against zero-order-hold Jacobi: the largest factor e_zoh / e over pairs of
// runs where the other run took no more wall time than the zero-order-hold one. Sets
// best_scheme_ (the plots keep it).
json Bench::best_vs_zero_order_hold() {
  json ten_x = json::object();
  std::vector<std::pair<double, double>> zoh;
  for (std::size_t i = 0; i < specs_.size(); ++i)
    if (variants_[specs_[i].variant].zero_order_hold_jacobi && results_[i].status == "ok" && std::isfinite(results_[i].rms_rel))
      zoh.push_back({results_[i].wall_time_s, results_[i].rms_rel});
  double best = 0;
  json where;
  bool any_other_ok = false;
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    if (variants_[specs_[i].variant].zero_order_hold_jacobi || results_[i].status != "ok") continue;
    any_other_ok = true;
    // A refused (below reference accuracy) error is bounded by the reference's error.
    const double e = std::isfinite(results_[i].rms_rel) ? results_[i].rms_rel : results_[i].rms_rel_bound;
    if (!(e > 0)) continue;
    for (const auto& [wz, ez] : zoh)
      if (results_[i].wall_time_s <= wz && ez / e > best) {
        best = ez / e;
        where = {{"scheme", variants_[specs_[i].variant].name}, {"solver", specs_[i].solver}, {"rtol", specs_[i].rtol},
                 {"step_s", specs_[i].h}, {"wall_time_s", results_[i].wall_time_s}, {"rms_rel", e},
                 {"bounded_by_reference", !std::isfinite(results_[i].rms_rel)}, {"zoh_wall_time_s", wz}, {"zoh_rms_rel", ez}};
      }
  }
  ten_x["definition"] = "max over run pairs of rms_rel(zero-order-hold Jacobi) / rms_rel(other) where the other run's wall time <= the zero-order-hold run's";
  ten_x["zoh_stable_points"] = zoh.size();
  bool zoh_swept = false;
  for (const auto& v : variants_) zoh_swept = zoh_swept || v.zero_order_hold_jacobi;
  if (!zoh_swept) {
    ten_x["factor"] = nullptr;
    ten_x["met"] = nullptr;
    ten_x["note"] = "zero-order-hold Jacobi not swept (--schemes)";
  } else if (zoh.empty()) {
    ten_x["factor"] = nullptr;
    ten_x["met"] = any_other_ok;
    ten_x["note"] = any_other_ok ? "zero-order-hold Jacobi is unstable at every swept H; other schemes are not"
                                 : "no stable run";
  } else if (!(best > 0)) {
    ten_x["factor"] = nullptr;
    ten_x["met"] = nullptr;
    ten_x["note"] = "no other run with a measurable error at no more wall time than a zero-order-hold run";
  } else {
    ten_x["factor"] = best;
    ten_x["met"] = best >= 10;
    ten_x["at"] = where;
    if (where.is_object()) best_scheme_ = where["scheme"].get<std::string>();
  }
  return ten_x;
}

// --- adaptive against fixed H ----------------------------------------------------------

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

// --- the table and the JSON --------------------------------------------------------------

// One line of the table.
std::string Bench::table_line(const std::string& scheme, const std::string& h, const RunSpec& r, const RunResult& res) const {
  char line[512];
  std::snprintf(line, sizeof line, "%-22s %-9s %-11s %-6s %-9s %-10s %-10s %-9s %-9s\n", scheme.c_str(), h.c_str(),
                r.solver.c_str(), num(r.rtol, "%.0e").c_str(), res.status.c_str(),
                res.rms_below_reference ? "<ref" : num(res.rms_rel).c_str(),
                res.max_below_reference ? "<ref" : num(res.max_rel).c_str(), num(res.wall_time_s, "%.3f").c_str(),
                res.solver.is_object() ? std::to_string(res.solver.value("steps", 0L)).c_str() : "-");
  return line;
}

void Bench::print_rows() {
  out_ << "mechsim bench " << scene_name_ << ": errors are the RMS (max) of the worst compared signal, relative to the reference range; '<ref' = below the reference's own error\n";
  char line[512];
  std::snprintf(line, sizeof line, "%-22s %-9s %-11s %-6s %-9s %-10s %-10s %-9s %-9s\n", "scheme", "H", "solver", "rtol", "status",
                "rms_rel", "max_rel", "wall_s", "steps");
  out_ << line;
  for (std::size_t i = 0; i < specs_.size(); ++i)
    out_ << table_line(variants_[specs_[i].variant].name, time_text(specs_[i].h), specs_[i], results_[i]);
  for (std::size_t i = 0; i < adaptive_specs_.size(); ++i)
    out_ << table_line(scheme_name(adaptive_specs_[i]), "tol " + tol_text(adaptive_specs_[i].tolerance), adaptive_specs_[i],
                       adaptive_results_[i]);
}

// The observed orders, the DDS spot checks and the best scheme against zero-order hold.
void Bench::print_findings(const json& orders, const json& ten_x) {
  out_ << "observed order (cvode_bdf, rtol " << num(tightest_rtol(), "%.0e") << "):";
  for (const auto& o : orders)
    out_ << "  " << o["scheme"].get<std::string>() << " " << (o["order"].is_number() ? num(o["order"].get<double>(), "%.2f") : "-");
  out_ << "\n";
  for (const auto& d : dds_)
    out_ << "DDS spot check " << d["scheme"].get<std::string>() << " H " << time_text(d["step_s"].get<double>()) << ": "
         << d.value("status", "?") << ", outputs " << (d.value("outputs_identical", false) ? "bit-identical to" : "DIFFERENT from")
         << " the in-process run, wall " << num(d.value("wall_time_s", kNaN)) << " s (in process "
         << (d["inproc_wall_time_s"].is_number() ? num(d["inproc_wall_time_s"].get<double>()) : "-") << " s)\n";
  out_ << "best scheme vs zero-order-hold Jacobi: "
       << (ten_x["factor"].is_number() ? num(ten_x["factor"].get<double>(), "%.3g") + "x" : ten_x.value("note", ""))
       << (ten_x["at"].is_object() ? " (" + ten_x["at"]["scheme"].get<std::string>() + " " + ten_x["at"]["solver"].get<std::string>() + " H " +
                                         time_text(ten_x["at"]["step_s"].get<double>()) + ")"
                                   : "")
       << "\n";
}

void Bench::print_adaptive_vs_fixed(const json& adaptive_vs_fixed) {
  for (const auto& c : adaptive_vs_fixed["curves"]) {
    auto factor_text = [](const json& f, const char* what) {
      std::string t = std::string(what) + " error ";
      if (f["best_factor"].is_number())
        return t + "x" + num(f["best_factor"].get<double>(), "%.3g") + " at tol " + tol_text(f["best_at_tolerance"].get<double>()) +
               " (target 5x: " + (f["target_5x_met"].get<bool>() ? "met" : "not met") + ")";
      return t + "no factor (target 5x: not met)";
    };
    out_ << c["scheme"].get<std::string>() << " vs best fixed H at equal wall time: " << factor_text(c, "max") << "; "
         << factor_text(c["rms"], "rms") << "\n";
    const auto steps_text = [](const json& f) {
      return f["best_factor_at_equal_steps"].is_number() ? "x" + num(f["best_factor_at_equal_steps"].get<double>(), "%.3g") : std::string("-");
    };
    out_ << "  against the same scheme at fixed H and equal macro steps: max error " << steps_text(c) << ", rms error "
         << steps_text(c["rms"]) << "\n";
    for (std::size_t k = 0; k < c["points"].size(); ++k) {
      const json& p = c["points"][k];
      const json& q = c["rms"]["points"][k];
      auto one = [](const json& x) {
        if (x["adaptive_below_reference_accuracy"].get<bool>()) return std::string("<ref");
        std::string t = x["adaptive_error"].is_number() ? num(x["adaptive_error"].get<double>()) : "-";
        if (x["fixed_error"].is_number()) t += " (fixed " + num(x["fixed_error"].get<double>()) + ")";
        else if (x["fixed_error"].is_string()) t += " (fixed: outside)";
        if (x["factor"].is_number()) t += " x" + num(x["factor"].get<double>(), "%.3g");
        if (x["factor_at_equal_steps"].is_number()) t += " [equal steps x" + num(x["factor_at_equal_steps"].get<double>(), "%.3g") + "]";
        return t;
      };
      out_ << "  tol " << tol_text(p["tolerance"].get<double>()) << ": " << p["status"].get<std::string>() << ", "
           << p["macro_steps"].get<long>() << " macro steps, wall "
           << (p["wall_time_s"].is_number() ? num(p["wall_time_s"].get<double>()) : "-") << " s, max " << one(p) << ", rms "
           << one(q) << "\n";
    }
  }
}

void Bench::write_json(const json& orders, const json& ten_x, const json& adaptive_vs_fixed, double duration) {
  json refs = json::array();
  for (const auto& [key, ref] : refs_)
    refs.push_back({{"coupling_element", key.first}, {"step_s", key.second}, {"error", ref->error},
                    {"rtol", ref->run.rtol}, {"wall_time_s", ref->run.wall_time_s}, {"accuracy", ref->accuracy_json}});
  for (std::size_t i = 0; i < adaptive_specs_.size(); ++i)
    if (adaptive_results_[i].reference.is_object()) {
      json a = adaptive_results_[i].reference;
      a["scheme"] = scheme_name(adaptive_specs_[i]);
      refs.push_back(a);
    }
  json rows = json::array();
  for (std::size_t i = 0; i < specs_.size(); ++i) rows.push_back(row_json(specs_[i], results_[i]));
  for (std::size_t i = 0; i < adaptive_specs_.size(); ++i) rows.push_back(row_json(adaptive_specs_[i], adaptive_results_[i]));
  json schemes = json::array();
  for (auto& v : variants_) schemes.push_back(v.name);
  json doc{{"schema_version", tools::schema_version},
           {"provenance", tools::provenance(opt_.scene_path)},
           {"kind", "bench"},
           {"scene", scene_name_},
           {"overrides", opt_.overrides},
           {"options", {{"quick", opt_.quick}, {"repeat", opt_.repeat}, {"steps_s", grid_}, {"solvers", solvers_}, {"rtol", opt_.rtol}, {"rtols", rtols_},
                        {"tolerances", tolerances_},
                        {"schemes", schemes}}},
           {"schemes_refused", refused_variants_},
           {"references", refs},
           {"rows", rows},
           {"orders", orders},
           {"dds_checks", dds_},
           {"best_vs_zero_order_hold", ten_x},
           {"adaptive_vs_fixed", adaptive_vs_fixed},
           {"duration_s", duration}};
  if (!opt_.plots_dir.empty())
    doc["files"] = {{"work_precision_png", opt_.plots_dir + "/" + scene_name_ + "_work_precision.png"},
                    {"error_vs_step_png", opt_.plots_dir + "/" + scene_name_ + "_error_vs_step.png"}};
  tools::write_json_file(opt_.json_path, doc);
}

// The nodes print their own lines ("done: ...") on stdout: this keeps them out of the
// table while it lives.
class StdoutToDevNull {
 public:
  StdoutToDevNull() {
    std::fflush(stdout);
    saved_ = dup(1);
    if (FILE* null = std::fopen("/dev/null", "w")) {
      dup2(fileno(null), 1);
      std::fclose(null);
    }
  }
  ~StdoutToDevNull() {
    std::fflush(stdout);
    if (saved_ >= 0) {
      dup2(saved_, 1);
      close(saved_);
    }
  }
  StdoutToDevNull(const StdoutToDevNull&) = delete;
  StdoutToDevNull& operator=(const StdoutToDevNull&) = delete;

 private:
  int saved_ = -1;
};

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
    const StdoutToDevNull quiet_nodes;
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
  plots(specs_, results_, orders);
  if (!opt_.json_path.empty()) write_json(orders, ten_x, adaptive_vs_fixed_json, duration);
  if (!opt_.keep_work_dir) {
    std::error_code ec;
    fs::remove_all(opt_.work_dir, ec);
  }
  return 0;
}

}  // namespace

int run_bench(const BenchOptions& options, std::ostream& out) {
  Bench b(options, out);
  return b.run();
}

}  // namespace mechsim::bench

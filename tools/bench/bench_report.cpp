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

#include "json_io.h"
#include "provenance.h"

namespace mechsim::bench {

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
         << (d.contains("inproc_wall_time_s") && d["inproc_wall_time_s"].is_number() ? num(d["inproc_wall_time_s"].get<double>()) : "-") << " s)\n";
  // ten_x and d are const: operator[] on a key they lack is undefined behaviour (it crashed
  // now and then after a bench without a best pair), so optional keys are tested first.
  out_ << "best scheme vs zero-order-hold Jacobi: "
       << (ten_x["factor"].is_number() ? num(ten_x["factor"].get<double>(), "%.3g") + "x" : ten_x.value("note", ""))
       << (ten_x.contains("at") && ten_x["at"].is_object() ? " (" + ten_x["at"]["scheme"].get<std::string>() + " " + ten_x["at"]["solver"].get<std::string>() + " H " +
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
        if (x.contains("factor") && x["factor"].is_number()) t += " x" + num(x["factor"].get<double>(), "%.3g");
        if (x.contains("factor_at_equal_steps") && x["factor_at_equal_steps"].is_number()) t += " [equal steps x" + num(x["factor_at_equal_steps"].get<double>(), "%.3g") + "]";
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

}  // namespace mechsim::bench

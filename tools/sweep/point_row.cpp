#include "point_row.h"

#include <cmath>
#include <filesystem>

#include "assessment_json.h"
#include "json_io.h"
#include "scene_override.h"

namespace mechsim::sweep {

using nlohmann::json;
using tools::finite_or_null;

json figure_columns(const json& report) {
  json out = json::object();
  if (!report.is_array()) return out;
  for (const auto& f : report) {
    const std::string name = f.value("stat", "?") + "(" + f.value("signal", "?") + ")";
    for (const auto& [k, v] : f.items()) {
      if (k == "at" && v.is_object()) out[name + ".at(" + v.value("signal", "?") + ")"] = v["value"];
      else if (v.is_number() && k != "target") out[k == "value" ? name : name + "." + k] = v;
    }
  }
  return out;
}

json point_row(const Point& point, const SceneRun& run) {
  json row;
  row["point"] = point.index;
  for (const auto& v : point.values) {
    row[v.key] = finite_or_null(v.number);
    row[v.key + ".text"] = v.text;
  }
  row["outcome"] = run.outcome;
  row["reason"] = run.reason;
  row["steps"] = run.steps;
  row["wall_time_s"] = run.wall_time_s;
  row["worst_max_rel_error"] = nullptr;
  row["worst_max_rel_signal"] = "";
  row["worst_rms_rel_error"] = nullptr;
  row["worst_rms_rel_signal"] = "";
  if (!run.comparison) return row;
  double worst_max = -1, worst_rms = -1;
  for (const auto& s : run.comparison->signals) {
    const std::string name = s.signal.full_name();
    const double max_rel = s.error.finite ? s.error.max_rel : INFINITY, rms_rel = s.error.finite ? s.error.rms_rel : INFINITY;
    row[name + ".max_rel_error"] = finite_or_null(max_rel);
    row[name + ".rms_rel_error"] = finite_or_null(rms_rel);
    if (max_rel > worst_max) {
      worst_max = max_rel;
      row["worst_max_rel_error"] = finite_or_null(max_rel);
      row["worst_max_rel_signal"] = name;
    }
    if (rms_rel > worst_rms) {
      worst_rms = rms_rel;
      row["worst_rms_rel_error"] = finite_or_null(rms_rel);
      row["worst_rms_rel_signal"] = name;
    }
  }
  const json figures = figure_columns(tools::report_figures_json(run.comparison->report));  // items() of a named value
  for (const auto& [k, v] : figures.items()) row[k] = v;
  return row;
}

std::vector<std::string> point_overrides(const std::vector<std::string>& base_overrides, const Point& point) {
  std::vector<std::string> o = base_overrides;
  for (const auto& set : point.sets()) o.push_back(tools::scene_override(set));
  return o;
}

json point_summary(const std::vector<std::string>& overrides, const json& row, const SceneRun& run) {
  json summary = {{"schema_version", tools::schema_version}, {"overrides", overrides}, {"row", row}};
  if (run.comparison) {
    const assess::ReferenceComparison& c = *run.comparison;
    json signals = json::object();
    for (const auto& s : c.signals)
      signals[s.signal.full_name()] = {{"unit", s.unit}, {"max_abs_error", finite_or_null(s.error.max_abs)},
                                       {"max_rel_error", finite_or_null(s.error.max_rel)},
                                       {"rms_abs_error", finite_or_null(s.error.rms_abs)},
                                       {"rms_rel_error", finite_or_null(s.error.rms_rel)},
                                       {"reference_range", s.error.range}, {"finite", s.error.finite}};
    summary["signals"] = signals;
    summary["report"] = tools::report_figures_json(c.report);
    summary["reference"] = {{"rtol", c.reference.rtol}, {"wall_time_s", c.reference.wall_time_s},
                            {"accuracy", tools::reference_accuracy_json(c.accuracy, c.reference_accuracy)}};
  }
  json nodes = json::array();
  for (const auto& n : run.inproc.nodes)
    nodes.push_back({{"name", n.name}, {"exit_code", n.exit_code}, {"solver_steps", n.last.solver_steps},
                     {"rhs_evals", n.last.rhs_evals}, {"message", n.last.message}});
  summary["nodes"] = nodes;
  summary["run_wall_time_s"] = run.run_wall_time_s;
  return summary;
}

json point_json(const Point& point) {
  json values = json::array();
  for (const auto& v : point.values) values.push_back({{"key", v.key}, {"text", v.text}, {"number", finite_or_null(v.number)}});
  return {{"index", point.index}, {"values", values}};
}

Point point_from_json(const json& j) {
  Point p;
  p.index = j.at("index").get<int>();
  for (const auto& v : j.at("values"))
    p.values.push_back({v.at("key").get<std::string>(), v.at("text").get<std::string>(),
                        v.at("number").is_number() ? v.at("number").get<double>() : NAN});
  return p;
}

json run_point(const std::string& scene_path, const std::vector<std::string>& base_overrides, const Point& point,
               const std::string& point_dir) {
  std::filesystem::create_directories(point_dir);  // a refused point leaves its summary too
  const std::vector<std::string> overrides = point_overrides(base_overrides, point);
  const SceneRun run = run_scene(scene_path, overrides, point_dir);
  json row = point_row(point, run);
  json summary = point_summary(overrides, row, run);
  summary["scene_file"] = scene_path;
  tools::write_json_file(point_dir + "/summary.json", summary);
  return row;
}

}  // namespace mechsim::sweep

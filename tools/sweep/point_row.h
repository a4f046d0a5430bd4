// A sweep point's result: its row of the sweep's table (flat: the point's keys, the
// outcome, steps, wall time, the worst errors, each compared signal's errors, the report
// figures) and the point's summary.json. One row layout for `mechsim sweep` and the Python
// package (docs/sweeps.md, "The table").
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "design.h"
#include "scene_run.h"

namespace mechsim::sweep {

// The row: "point", per key "KEY" (its number, null without one) and "KEY.text" (as handed
// to the scene), "outcome", "reason", "steps", "wall_time_s", "worst_max_rel_error",
// "worst_max_rel_signal", "worst_rms_rel_error", "worst_rms_rel_signal", per compared signal
// "SIGNAL.max_rel_error" and "SIGNAL.rms_rel_error", per report figure its numbers
// ("min(follower.contact_force)", "...t_s", "...at(cam.angle)", "step_response(x).rise_time_s").
nlohmann::json point_row(const Point& point, const SceneRun& run);

// The report figures (tools::report_figures_json's layout) flattened into row columns.
nlohmann::json figure_columns(const nlohmann::json& report);

// The point's summary.json: the row, the report figures beside the reference's, every
// signal's errors, the reference's accuracy, the nodes' solver figures.
nlohmann::json point_summary(const std::vector<std::string>& overrides, const nlohmann::json& row, const SceneRun& run);

// A point as JSON ({"index", "values": [{"key", "text", "number"}]}) and back, to hand it
// to another process (the Python package's executors).
nlohmann::json point_json(const Point& point);
Point point_from_json(const nlohmann::json& j);

// Runs one point of a sweep: the scene with `base_overrides` and the point's keys, its node
// logs and summary.json (the row, the report figures beside the reference's, every signal's
// errors, the reference's accuracy, the nodes' solver figures) in `point_dir`. Returns the row.
nlohmann::json run_point(const std::string& scene_path, const std::vector<std::string>& base_overrides, const Point& point,
                         const std::string& point_dir);

// The point's overrides: the base ones, then the point's keys (dotted, as the loader takes them).
std::vector<std::string> point_overrides(const std::vector<std::string>& base_overrides, const Point& point);

}  // namespace mechsim::sweep

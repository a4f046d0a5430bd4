// `mechsim cvt-map SCENE`: the operating maps of the push-belt CVT (docs/cvt.md). The CVT
// data is the first `cvt` participant's params (parsed by the node type's own parser,
// mechsim/catalog/cvt_params.h), else the thesis rig. The grid is design.cvt_map:
//   design:
//     cvt_map:
//       ratio_setting: {from: 5 mm, to: 55 mm, points: 5}     # or a list [5 mm, 30 mm]
//       torque: {from: 20 Nm, to: 120 Nm, points: 5}          # T_C, the intermediate-body torque
//       speed: {from: 1000 rpm, to: 5000 rpm, points: 5}      # n_C, the input speed
// (defaults: the thesis's 5 × 5 × 5 grid). Every grid point is evaluated with the L1 model and
// with L0 for its deviation.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mechsim/config/scene.h"
#include "mechsim/catalog/cvt_params.h"
#include "mechsim/models/cvt/cvt_model.h"

namespace mechsim::tools::cvt_map {

// Points per axis from the command line (--points, --s-points, ...): the axis keeps its first
// and last value and is resampled evenly.
struct GridOptions {
  std::optional<int> s_points, torque_points, speed_points;
};

struct CvtMapResult {
  std::string scene_name, scene_file;
  std::vector<std::string> overrides;
  std::string source;  // "participants.cvt.params" or "defaults"
  std::vector<std::string> notes;
  cosim::CvtConfig config;
  std::vector<double> s, torque, speed;  // axes, SI: m, Nm, rad/s
  // Row-major [s][torque][speed].
  std::vector<models::cvt::CvtResult> l1, l0;
  models::cvt::LinkCurvatures curvatures;
  std::size_t index(std::size_t is, std::size_t it, std::size_t in) const {
    return (is * torque.size() + it) * speed.size() + in;
  }
};

// Throws config::ConfigError naming the file and key path.
CvtMapResult analyse_scene(const config::Scene& scene, const std::vector<std::string>& overrides,
                           const GridOptions& grid = {});

// The printed report: source, grid, ranges, L0 deviation, and per ratio setting the tables
// of T_1, F_K, η_PB and η_SYS over torque (rows) and speed (columns).
std::vector<std::string> summary_lines(const CvtMapResult& result);
nlohmann::json report_json(const CvtMapResult& result);

struct PlotOutcome {
  std::vector<std::string> files;
  std::vector<std::string> problems;
};
// efficiency.png, clamping_force.png, link_link_stress.png in `dir` (created if needed).
PlotOutcome write_plots(const std::string& dir, const CvtMapResult& result);

}  // namespace mechsim::tools::cvt_map

// The PNG plots of `mechsim cam-design` (docs/cam-design.md), one figure per file:
//   roller follower: motion_law, pressure_angle_curvature, forces, drive_torque_flywheel,
//                    follower_error, cam_contour
//   flat face:       motion_law, cam_contour, torque_power
// Plots are never fatal: a missing gnuplot is reported in `problems`.
#pragma once

#include <string>
#include <vector>

#include "cam_design_report.h"
#include "plot.h"

namespace mechsim::tools::cam_design {

struct NamedFigure {
  std::string file_name;  // "motion_law.png"
  plot::Figure figure;
};

std::vector<NamedFigure> design_figures(const CamDesignResult& result);

struct PlotOutcome {
  std::vector<std::string> files;     // written PNGs (full paths)
  std::vector<std::string> problems;  // "<file>: <why>" for each figure not written
};

// Creates `dir` if needed. Throws std::runtime_error when the directory cannot be created.
PlotOutcome write_plots(const std::string& dir, const CamDesignResult& result);

}  // namespace mechsim::tools::cam_design

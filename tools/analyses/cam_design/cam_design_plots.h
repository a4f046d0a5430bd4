// The PNG plots of `mechsim cam-design` (docs/cam-design.md), one figure per file:
//   roller follower: motion_law, pressure_angle_curvature, forces, drive_torque_flywheel,
//                    follower_error, cam_contour
//   flat face:       motion_law, cam_contour, torque_power
// Plots are never fatal: a missing gnuplot is reported in `problems`.
#pragma once

#include <string>
#include <vector>

#include "cam_design_report.h"
#include "figure_files.h"

namespace mechsim::tools::cam_design {

using plot::NamedFigure;
using plot::PlotOutcome;

std::vector<NamedFigure> design_figures(const CamDesignResult& result);

// The design's figures in `dir` (plot::write_figures).
PlotOutcome write_plots(const std::string& dir, const CamDesignResult& result);

}  // namespace mechsim::tools::cam_design

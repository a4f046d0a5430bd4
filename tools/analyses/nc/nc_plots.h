// The PNG plots of the NC analyses (docs/nc-analyses.md), one figure per file:
//   motor-bode   bode.png, bode_b3_variants.png, bode_load_inertia.png
//                (magnitude and phase over a log frequency axis)
//   slide-modes  f0_vs_position.png, f0_vs_diameter.png, model3_convergence.png
// Plots are never fatal: a missing gnuplot is reported in `problems`.
#pragma once

#include <string>
#include <vector>

#include "motor_bode.h"
#include "plot.h"
#include "slide_modes.h"

namespace mechsim::tools::nc_analyses {

struct NamedFigure {
  std::string file_name;  // "bode.png"
  plot::Figure figure;
};

std::vector<NamedFigure> motor_bode_figures(const MotorBodeResult& result);
std::vector<NamedFigure> slide_modes_figures(const SlideModesResult& result);

struct PlotOutcome {
  std::vector<std::string> files;     // written PNGs (full paths)
  std::vector<std::string> problems;  // "<file>: <why>" for each figure not written
};

// Creates `dir` if needed. Throws std::runtime_error when the directory cannot be created.
PlotOutcome write_figures(const std::string& dir, const std::vector<NamedFigure>& figures);

}  // namespace mechsim::tools::nc_analyses

// The PNG plots of the NC analyses (docs/nc-analyses.md), one figure per file:
//   motor-bode   bode.png, bode_b3_variants.png, bode_load_inertia.png
//                (magnitude and phase over a log frequency axis)
//   slide-modes  f0_vs_position.png, f0_vs_diameter.png, model3_convergence.png
// Plots are never fatal: a missing gnuplot is reported in `problems`.
#pragma once

#include <string>
#include <vector>

#include "figure_files.h"
#include "motor_bode.h"
#include "slide_modes.h"

namespace mechsim::tools::nc_analyses {

using plot::NamedFigure;
using plot::PlotOutcome;
using plot::write_figures;

std::vector<NamedFigure> motor_bode_figures(const MotorBodeResult& result);
std::vector<NamedFigure> slide_modes_figures(const SlideModesResult& result);

}  // namespace mechsim::tools::nc_analyses

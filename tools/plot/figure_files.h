// A command's figures written as PNG files into one folder (cam-design, motor-bode,
// slide-modes): each figure under its own file name. Plots are never fatal: a figure that
// cannot be drawn (gnuplot missing or failing) is reported in `problems`.
#pragma once

#include <string>
#include <vector>

#include "plot.h"

namespace mechsim::plot {

struct NamedFigure {
  std::string file_name;  // "bode.png"
  Figure figure;
};

struct PlotOutcome {
  std::vector<std::string> files;     // written PNGs (full paths)
  std::vector<std::string> problems;  // "<file>: <why>" for each figure not written
};

// Creates `dir` if needed. Throws std::runtime_error when the directory cannot be created.
PlotOutcome write_figures(const std::string& dir, const std::vector<NamedFigure>& figures);

}  // namespace mechsim::plot

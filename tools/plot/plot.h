// Line plots to PNG through gnuplot, for the `mechsim` commands' figures.
//
// A figure is a column of panels sharing the width; each panel has its own axes and
// series. write_png() writes one data file per series and a readable gnuplot script into
// a temporary directory, runs `gnuplot` (pngcairo, or the plain png terminal when cairo
// is missing) and moves the image into place. Plots are never fatal: a missing or
// failing gnuplot is reported through the return value.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mechsim::plot {

struct Series {
  std::string label{};
  std::vector<double> x{}, y{};  // same length; NaN leaves a gap
  std::string style = "lines";   // "lines", "points", "linespoints", "dashed"
};

struct Panel {
  // Default member initializers let callers use designated initializers without
  // -Wmissing-field-initializers noise.
  std::string title{}, xlabel{}, ylabel{};
  std::vector<Series> series{};
  bool logx = false, logy = false;
  std::optional<std::pair<double, double>> yrange{};     // default: autoscale
  std::vector<std::pair<double, std::string>> hlines{};  // reference lines (y, label)
  bool equal_axes = false;                               // one unit is as long on x as on y
};

struct Figure {
  std::string title{};
  std::vector<Panel> panels{};  // stacked vertically
  int width_px = 1000;
  int height_px_per_panel = 320;
};

// Writes the PNG. Returns false and explains why in *why (if given) when the figure is
// malformed, gnuplot is missing or fails, or the file cannot be written.
bool write_png(const Figure& figure, const std::string& png_path, std::string* why = nullptr);

// True when a `gnuplot` executable is found on PATH.
bool gnuplot_available();

}  // namespace mechsim::plot

// `mechsim sweep`: a design study of one scene (docs/sweeps.md). The points of a design
// (design.h) each run in full in this process (scene_run.h), --jobs of them at a time on
// threads of their own; a point that is refused or diverges is a row with its reason. The
// sweep writes DIR/points/NNNNN/summary.json per point, then DIR/sweep.csv, DIR/sweep.json
// (the table: table.h) and DIR/plots/*.png (each figure and the worst error against each
// varied key), with a progress line and an ETA on stderr. --resume takes the rows of points
// already in DIR (same scene, overrides and design) instead of running them again.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "design.h"

namespace mechsim::sweep {

struct SweepOptions {
  std::string scene_path;
  std::vector<std::string> overrides;  // the base --set, dotted (every point)
  std::vector<std::string> vary;       // "KEY=SPEC"
  DesignOptions design;
  int jobs = 0;                        // 0 = the machine's cores
  std::string out_dir = "sweep";
  bool resume = false;
  bool progress = true;
  bool plots = true;
  double max_hours = 24;               // refuse a sweep estimated to take longer (after its first points)
};

// The design's points and its JSON description (scene, overrides, method, samples, seed,
// vary), for DIR/design.json and --resume. Throws DesignError.
struct Study {
  std::vector<VarySpec> specs;
  std::vector<Point> points;
  nlohmann::json design;
};
Study plan_study(const SweepOptions& options);

// Every point's scene (of a design over 2000 points, 2000 spread over it) loaded and planned
// before any runs: the reasons of the points the scene refuses (index -> reason, the rest absent). Throws DesignError when a varied key is
// not one the scene has (every point would be refused for it) or every point is refused.
std::map<int, std::string> check_points(const SweepOptions& options, const Study& study);

// DIR/points/NNNNN, where point `index` leaves its files.
std::string point_dir(const std::string& out_dir, int index);

// Before the points run: with --resume, refuses (DesignError) a DIR that holds another study;
// writes DIR/design.json.
void begin_study(const SweepOptions& options, const Study& study);

// With --resume: the row point `point` left in DIR when it finished with the same overrides.
std::optional<nlohmann::json> finished_row(const SweepOptions& options, const Point& point);

// The table and plots of the rows (one per point, any order): DIR/sweep.csv, DIR/sweep.json
// and DIR/plots/. Returns the table document (sweep.json's contents). Plot problems go to `problems`.
nlohmann::json write_outputs(const SweepOptions& options, const Study& study, std::vector<nlohmann::json> rows,
                             std::vector<std::string>* problems = nullptr);

// The whole sweep; a summary on `out`. Returns 0 (every point has its row, whatever its
// outcome), 2 bad input (nothing ran), 3 stopped by --max-hours after its first points, 130
// interrupted (the finished rows are written: --resume goes on).
int run_sweep(const SweepOptions& options, std::ostream& out);

}  // namespace mechsim::sweep

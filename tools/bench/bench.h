// `mechsim bench`: work-precision sweeps of one scene (docs/accuracy.md).
//
// Sweeps the macro step H, the coupling scheme of the scene's connections (the schemes the
// scene grammar accepts and the scene's connections can take), the node solver and its
// tolerance, runs each point over the in-process transport (cosim::run_inproc: the node
// code on one executor thread of this process) and a few spot checks over DDS (`mechsim launch`
// processes), and measures each run against the monolithic reference at the same H
// (assess::compare_signal on the scene's `compare:` outputs). An error that is not larger
// than the reference's own error estimate (cosim::estimate_reference_error: a re-run at a
// 100x tighter tolerance) is never reported as a number: it is marked "below reference
// accuracy". Adaptive points: the shipped scheme (its orders with every Jacobi edge quadratic,
// and the best fixed-H scheme at the scene's H) with an adaptive macro step (time.step:
// adaptive) at each of --tolerances, each measured against its own reference sampled at the
// instants its run took, and set against the best fixed-H error reached at the same wall
// time ("adaptive_vs_fixed").
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "scheme_variants.h"

namespace mechsim::bench {

struct BenchOptions {
  std::string scene_path;
  std::vector<std::string> overrides;   // "dotted.key=value", applied to every run
  std::string json_path;                // "" = no JSON
  std::string plots_dir;                // "" = no PNG
  std::vector<double> steps;            // macro steps in s; empty = the scene's decade range
  std::vector<std::string> schemes;     // scheme names to keep; empty = all valid for the scene
  std::vector<std::string> solvers;     // empty = cvode_bdf cvode_adams arkode_erk arkode_dirk
  std::vector<double> rtols;            // node tolerances swept with cvode_bdf; empty = default
  double rtol = 1e-6;                   // node tolerance of the solver sweep (atol = rtol/1000)
  // Coupling tolerances of the adaptive points (time.tolerance); nullopt = default
  // ({1e-2, 1e-3} with quick, else {1e-2, 3e-3, 1e-3, 3e-4, 1e-4}); empty = no adaptive points.
  std::optional<std::vector<double>> tolerances;
  bool quick = false;                   // small subset for CI
  int dds_checks = -1;                  // DDS spot checks; -1 = default (2, quick 1)
  int repeat = 1;                       // every run timed this often, the fastest kept (short runs more: see bench.cpp)
  std::string mechsim_exe;              // for the DDS spot checks; "" = /proc/self/exe
  std::string work_dir;                 // scratch; "" = a fresh directory under /tmp
  bool keep_work_dir = false;
};

// Slope of log(error) against log(H), least squares. Points with a non-positive or
// non-finite error are skipped; NaN with fewer than 3 points.
double fit_order(const std::vector<double>& h, const std::vector<double>& error);

// Parses "25 us,50 us,1ms" (comma separated quantities of time) to seconds. Throws
// std::invalid_argument with the offending entry.
std::vector<double> parse_steps(const std::string& text);

// Parses "1e-2,1e-3" (comma separated numbers in (0, 1)) to the adaptive tolerances, sorted
// loosest first; "none" or "" = none. Throws std::invalid_argument with the offending entry.
std::vector<double> parse_tolerances(const std::string& text);

// The lower envelope of (wall time, error) points at wall time `wall`: the least error of the
// points with no more wall time, interpolated log-log between the envelope's corners (the
// points that lower it). Points with a non-positive or non-finite wall time or error are
// skipped; NaN when `wall` is outside the points' wall time range. `lo`/`hi` (optional) get
// the indices (into `points`) of the corners it was interpolated between (equal at a corner
// or on the flat part after the last one).
double envelope_at(const std::vector<std::pair<double, double>>& points, double wall, int* lo = nullptr, int* hi = nullptr);

// Runs the bench; prints the table on `out`, progress on stderr. Returns the exit code:
// 0 done, 1 a run could not be measured at all (the reference failed), 2 bad scene/options.
int run_bench(const BenchOptions& options, std::ostream& out);

}  // namespace mechsim::bench

// A finished run against the monolithic reference: the reference run on the instants the
// nodes logged, its own accuracy, every compared signal's error and its cause, the report's
// figures beside the reference's. Computed here; `mechsim launch` writes it into the run
// folder (signals.csv, signals.png) and the summary (tools/launch/run_comparison.h).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mechsim/assess/reference_accuracy.h"
#include "mechsim/assess/report_figures.h"
#include "mechsim/assess/signal_compare.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/composer.h"
#include "mechsim/cosim/scene_plan.h"

namespace mechsim::assess {

struct ComparedSignal {
  config::SignalRef signal;
  std::string unit;                    // of the node output
  std::vector<double> cosim, reference;  // on the instants of ReferenceComparison::t
  SignalError error;
  ErrorCause cause;
};

struct ReferenceComparison {
  cosim::ReferenceRun reference;        // its log's first column is t
  cosim::ReferenceAccuracy accuracy;    // of the reference, by a tighter re-run
  std::vector<SignalAccuracy> reference_accuracy;  // the same per compared signal
  std::vector<double> t;
  std::vector<ComparedSignal> signals;  // the scene's `compare:` entries, in order
  std::vector<ReportFigure> report;     // with the reference's figures
  // An adaptive step without time.scales: the range of every scaled quantity in this run
  // (participant -> field -> range), the scales to write in the scene.
  std::optional<std::map<std::string, std::map<std::string, double>>> suggested_scales;
  std::map<std::string, int> reference_event_counts;  // by kind
  // Nodes stepping themselves inside the reference too (co-simulation FMUs: there is no
  // continuous model of them), so the errors measure the coupling only.
  std::vector<std::string> self_stepping;
};

// Runs the reference of `scene` on the instants the nodes of `plan` logged in `run_dir` and
// compares their output logs with it. Throws std::runtime_error when a node log and the
// reference differ in length.
ReferenceComparison compare_with_reference(const config::Scene& scene, const cosim::ScenePlan& plan, const std::string& run_dir);

}  // namespace mechsim::assess

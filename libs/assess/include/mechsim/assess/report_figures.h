// The scene's `report:` figures of a run (extrema, final value, time in a state, step
// response, energy balance), each optionally beside the reference's value and the relative
// difference. Shared by `launch`, `reference` and the bench, which write them out.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mechsim/config/scene.h"

namespace mechsim::assess {

// Looks up a signal's time series by "participant.output" (empty span when unknown).
using SeriesLookup = std::function<std::span<const double>(const config::SignalRef&)>;

// Step-response figures of y(t) towards `target` from its initial value.
struct StepResponse {
  double rise_time = 0.0;      // s, 10 % -> 90 % of the step
  double overshoot = 0.0;      // fraction of the step beyond the target (0 if none)
  double settling_time = 0.0;  // s from t0 until y stays within band * step of the target
  double final_value = 0.0;
  bool settled = false;        // y ended inside the band
};
StepResponse step_response(std::span<const double> t, std::span<const double> y, double target, double band);

// Another signal evaluated where an extremum lies (`at:`), in its display unit.
struct ValueAt {
  std::string signal;
  double value = 0.0;
  std::string unit;  // "SI" when the scene names none
};

// A step_response figure: the response towards the target (written or the last value).
struct StepFigure {
  StepResponse response;
  double target = 0.0;
  double final_error = 0.0;  // final value - target
};

// supplied work = dissipated work + change of the stored energies [J], each term by name.
struct EnergyBalance {
  double supplied = 0.0, dissipated = 0.0, stored_change = 0.0;
  double residual = 0.0;           // supplied - dissipated - stored change
  double relative_residual = 0.0;  // |residual| / |supplied|
  std::map<std::string, double> terms;
};

// What one `report:` entry computes on one run; which members are set follows the stat:
// min/max/max_abs: value, t (and at); final, time_true: value (and at); step_response: step;
// energy_balance: energy.
struct FigureValues {
  std::optional<double> value;
  std::optional<double> t;
  std::optional<ValueAt> at;
  std::optional<StepFigure> step;
  std::optional<EnergyBalance> energy;
};

// |run - reference| / |reference| of the figures both have.
struct FigureDifferences {
  std::optional<double> value, rise_time, settling_time, final_value, overshoot;
  std::optional<double> supplied, dissipated, stored_change;
};

struct ReportFigure {
  std::string stat;
  std::string signal;  // "participant.output"
  FigureValues run;
  std::optional<FigureValues> reference;        // with a reference that has the signals
  std::optional<FigureDifferences> difference;  // set with `reference`
};

// One figure per `report:` entry whose signals the run has, in the scene's order. With
// `reference` given, each figure also carries the reference's values and the differences.
std::vector<ReportFigure> report_figures(const config::Scene& scene, std::span<const double> t, const SeriesLookup& series,
                                         const SeriesLookup* reference = nullptr);

}  // namespace mechsim::assess

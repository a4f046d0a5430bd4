// `mechsim slide-modes`: the torsional eigenfrequency models of the slide drive train of a
// scene (spec nc_slide.md §2): model 1 (two inertias), model 2 (grounded chain, both
// frequencies), model 3 (continuous shaft, the report's N Ritz shapes and a converged value),
// the convergence of model 3 by Rayleigh–Ritz and by the FE chain, and the sweeps of f0 over
// the slide position and the spindle diameter.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/models/nc/slide_torsion.h"
#include "nc_case.h"
#include "nc_design_settings.h"

namespace mechsim::tools::nc_analyses {

struct ConvergencePoint {
  int count;           // Ritz shapes N or FE elements
  double frequency_hz;
};

struct PositionPoint {
  double position;      // x along the spindle from its drive end [m]
  double ritz_hz;       // model 3, settings.ritz_shapes shapes
  double converged_hz;  // model 3, FE chain with settings.sweep_fe_elements elements
};

struct DiameterPoint {
  double diameter;  // [m]
  double model1_hz;
  models::nc::GroundedChainFrequencies model2;
  double model3_hz;            // at the analysed slide position, settings.ritz_shapes shapes
  double model3_converged_hz;  // FE chain, settings.sweep_fe_elements elements
  double coupling_equivalent_length;  // the coupling's stand-in piece of model 3 [m]: the same at every d
};

struct SlideModesResult {
  std::string scene_name;
  std::string scene_file;
  std::vector<std::string> overrides;
  SlideModesSettings settings;
  SlideCase slide;
  double slide_position;  // x of model 3 [m]

  double model1_hz;
  models::nc::GroundedChainFrequencies model2;
  double model3_hz;              // settings.ritz_shapes shapes (the report: 3)
  double model3_converged_hz;    // FE chain, finest mesh of settings.fe_convergence
  std::optional<double> model3_extrapolated_hz;  // Richardson (order 2), two finest FE meshes
  std::vector<ConvergencePoint> ritz_convergence, fe_convergence;

  std::vector<PositionPoint> f0_vs_position;   // settings.position_points over 0..l
  PositionPoint f0_max;  // the sweep point with the highest converged f0
  // The first free–free mode's node on the equivalent shaft, x = (l − l_eq)/2, where the
  // slide inertia drops out: f0 = sqrt(G/ρ)/(2(l_eq + l)). Empty when it lies off the
  // spindle or the coupling inertia is lumped (the shaft is then no longer uniform).
  struct ModeNode {
    double position;      // x [m]
    double frequency_hz;  // closed form
  };
  std::optional<ModeNode> first_mode_node;
  std::vector<DiameterPoint> f0_vs_diameter;
};

// Throws config::ConfigError for a refused scene and std::exception for anything else.
SlideModesResult analyse_slide_modes(const config::Scene& scene, std::vector<std::string> overrides = {});

std::vector<std::string> slide_modes_summary(const SlideModesResult& result);

}  // namespace mechsim::tools::nc_analyses

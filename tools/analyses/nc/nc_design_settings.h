// The `design:` section of an NC scene: the settings of `mechsim motor-bode` and `mechsim
// slide-modes` (docs/nc-analyses.md). Every key is optional:
//
//   design:
//     motor: {...}        motor-tacho data when the scene has no `tachometer` participant
//     slide: {...}        slide drive data when the scene has no `slide` participant
//     motor_bode:  {frequency_range, points_per_decade, shaft_damping_variants, load_inertia}
//     slide_modes: {slide_position, ritz_shapes, lump_coupling_inertia, position_points,
//                   diameter_range, diameter_points, ritz_convergence, fe_convergence,
//                   sweep_fe_elements}
//
// Both commands validate the whole section, so a typo anywhere in it is refused by either.
// Bad input is a config::ConfigError naming the file and the key path.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "mechsim/config/config_node.h"

namespace mechsim::tools::nc_analyses {

struct MotorBodeSettings {
  double frequency_from_hz = 1.0;  // Bode plot range: the slow pole (17 Hz) to well above
  double frequency_to_hz = 1e4;    // the electrical pole (652 Hz)
  int points_per_decade = 200;
  std::vector<double> shaft_damping_variants{1e-4, 1e-2, 1e-1};  // b3 [N m s/rad], spec §1
  // Added to the rotor inertia I1. Empty: the scene's slide drive train (coupling, spindle,
  // slide) taken as one rigid inertia I_kopp + I_sp + I_slide.
  std::optional<double> load_inertia;
};

struct SlideModesSettings {
  // Slide position x along the spindle from its drive end [m] for model 3, its convergence
  // study and the diameter sweep. Empty: mid position l/2 (the report's).
  std::optional<double> slide_position;
  std::optional<config::ConfigNode> slide_position_node;  // to refuse a position beyond l
  int ritz_shapes = 3;                 // the report's N
  bool lump_coupling_inertia = false;  // the report folds I_kopp into the equivalent shaft
  int position_points = 61;            // f0(x) over 0 <= x <= l (25 mm steps on 1500 mm)
  double diameter_from = 0.031;        // f0(d), the report's 31-39 mm
  double diameter_to = 0.039;
  int diameter_points = 9;
  std::vector<int> ritz_convergence{2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64};             // shapes N
  std::vector<int> fe_convergence{4, 8, 16, 32, 64, 128, 256, 512, 1024};               // elements
  // FE elements of the "converged" curves of the sweeps: 256 is within 1e-5 of the limit
  // on the CNC 200 (O(h²)) at a sixteenth of the cost of 1024.
  int sweep_fe_elements = 256;
};

struct NcDesignSettings {
  std::optional<config::ConfigNode> motor;  // design.motor, parsed like a tachometer's params
  std::optional<config::ConfigNode> slide;  // design.slide, the slide drive data keys
  MotorBodeSettings motor_bode;
  SlideModesSettings slide_modes;
};

// `design` is Scene::design (absent: all defaults).
NcDesignSettings parse_nc_design_settings(const std::optional<config::ConfigNode>& design);


}  // namespace mechsim::tools::nc_analyses

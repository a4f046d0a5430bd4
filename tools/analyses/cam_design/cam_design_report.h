// The cam design report of a scene (spec cam.md §7): the analyses of libs/models run on
// the scene's roller follower, or on the flat-faced follower of §6 when the scene's
// `design:` section asks for it, plus the sampled curves the plots and exports need.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cam_design_case.h"
#include "cam_design_settings.h"
#include "mechsim/config/scene.h"
#include "mechsim/models/cam/design.h"
#include "mechsim/models/cam/flat_face.h"

namespace mechsim::tools::cam_design {

// Sample counts of the curves (0.1° for the contour: a chord error below 1e-4 mm on a
// 100 mm cam; 0.25° for the plots).
inline constexpr int contour_samples = 3600;
inline constexpr int cycle_samples = 1440;

struct RollerDesign {
  RollerCase input_case;
  models::cam::CamDesignReport report;
  std::vector<models::cam::ContourSample> contour;  // contour_samples over [0, 2π)
  std::vector<models::cam::CycleSample> cycle;      // cycle_samples over [0, 2π)
};

struct FlatFaceDesign {
  models::cam::FlatFaceParams params;
  models::cam::FlatFaceAnalysis analysis;
  double flywheel_inertia_kgm2;      // I = ΔE/(ω² K)
  double flywheel_disc_radius_m;     // R = (2I/(π t ρ))^(1/4), as for the roller follower
  models::cam::LiftOffSpeed lift_off;  // F_c = k (s + x0) + m s'' ω² first touches 0
  std::vector<models::cam::FlatFacePoint> points;  // contour_samples over [0, 2π)
};

struct CamDesignResult {
  std::string scene_name;
  std::string scene_file;
  std::vector<std::string> overrides;  // as given (--set), recorded in the JSON
  DesignSettings settings;
  std::optional<RollerDesign> roller;     // exactly one of the two is set
  std::optional<FlatFaceDesign> flat_face;
};

// Throws config::ConfigError for a refused scene (participants, law, design section) and
// std::exception for anything else.
CamDesignResult analyse_scene(const config::Scene& scene, std::vector<std::string> overrides = {});

// The main numbers, one per line, for the console.
std::vector<std::string> summary_lines(const CamDesignResult& result);

// The kinetostatic lift-off speed in one line ("lift-off speed (rigid follower): ...").
std::string lift_off_line(const models::cam::LiftOffSpeed& lift_off);

}  // namespace mechsim::tools::cam_design

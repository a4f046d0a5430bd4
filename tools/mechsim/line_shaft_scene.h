// The K-station line-shaft scene family (docs/line-shaft.md): the press line's motor, CVT,
// gear and press cam (station 1, as in config/scenes/press_line.yaml) and K - 1 further cam
// stations on one line shaft behind it, each driven through an elastic shaft segment from
// the station before. Station k's law, phase and load depend on k only, so the K-station
// scene is the (K+1)-station scene without its last station.
#pragma once

#include <string>

namespace mechsim::tools {

inline constexpr int kMaxStations = 32;

struct LineShaftOptions {
  int stations = 4;                 // K, 1..kMaxStations
  double segment_stiffness = 2e5;   // N m/rad, every segment
  double segment_damping = 200.0;   // N m s/rad
};

// The scene as YAML text (scene name line_shaft_<K>). Throws std::invalid_argument for K
// outside 1..kMaxStations or a non-positive stiffness / negative damping.
std::string line_shaft_scene(const LineShaftOptions& options);

}  // namespace mechsim::tools

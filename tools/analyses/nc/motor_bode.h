// `mechsim motor-bode`: the motor-tacho transfer function U_T/U_a of a scene (spec
// nc_slide.md §1): coefficients from the state equations, poles, DC gain, −3 dB corner, shaft
// resonance and its peak, the report's pole approximations (3)–(5) next to the exact poles,
// and the Bode curves of the model, of the shaft-damping variants and with a load inertia.
#pragma once

#include <array>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/models/nc/motor_tacho.h"
#include "nc_case.h"
#include "nc_design_settings.h"

namespace mechsim::tools::nc_analyses {

struct BodeCurve {
  std::vector<double> frequency_hz, magnitude_db, phase_deg;
};

// Everything the report states for one parameter set.
struct MotorTachoAnalysis {
  models::nc::MotorTachoParams params;
  models::nc::TransferFunction transfer_function;
  std::array<std::complex<double>, 4> poles;  // models::nc::poles order: slow, pair, electrical
  double dc_gain;
  double corner_hz;
  std::optional<models::nc::Resonance> resonance;  // empty when the shaft mode is overdamped
  models::nc::PoleApproximations approximations;
  // The exact poles the approximations stand for [Hz, |λ|/2π]: the slow real pole, the
  // electrical real pole and the shaft pair. With an overdamped shaft (four real poles)
  // only the slow one is named; none is named for parameters without two real poles.
  std::optional<double> exact_slow_pole_hz;
  std::optional<double> exact_electrical_pole_hz;
  std::optional<double> exact_shaft_pair_hz;
  double stiffness_ratio;   // max |λ| / min |λ|
  double real_part_ratio;   // max |Re λ| / min |Re λ|
  BodeCurve bode;
};

MotorTachoAnalysis analyse_motor_tacho(const models::nc::MotorTachoParams& params, const MotorBodeSettings& settings);

struct MotorBodeResult {
  std::string scene_name;
  std::string scene_file;
  std::vector<std::string> overrides;  // as given (--set), recorded in the JSON
  MotorBodeSettings settings;
  MotorCase motor;
  MotorTachoAnalysis nominal;
  std::vector<MotorTachoAnalysis> shaft_damping_variants;  // one per settings.shaft_damping_variants
  double load_inertia;           // added to I1 [kg m²]
  std::string load_inertia_source;  // "design.motor_bode.load_inertia" or how it was derived
  MotorTachoAnalysis with_load;
};

// Throws config::ConfigError for a refused scene and std::exception for anything else.
MotorBodeResult analyse_motor_bode(const config::Scene& scene, std::vector<std::string> overrides = {});

// The main numbers, one per line, for the console.
std::vector<std::string> motor_bode_summary(const MotorBodeResult& result);

}  // namespace mechsim::tools::nc_analyses

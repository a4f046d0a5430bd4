// Data of the CNC 200 slide drive train behind the motor (spec nc_slide.md §2): coupling,
// ball-screw spindle and slide, with the quantities derived from them. SI units.
#pragma once

#include <optional>

namespace mechsim::models::nc {

struct SlideDriveData {
  double slide_mass = 235.0;           // m [kg]
  double spindle_diameter = 0.035;     // d [m]
  double lead = 0.005;                 // s, slide travel per spindle revolution [m]
  double spindle_length = 1.5;         // l [m]
  double density = 7850.0;             // ρ [kg/m³]
  double shear_modulus = 8.0e10;       // G [Pa]
  double coupling_inertia = 2.5e-4;    // I_kopp [kg m²]
  double coupling_stiffness = 23e3;    // C_kopp [N m/rad]
  // The report's slide inertia reduced to the spindle, 2.1e-4 kg m² (it corresponds to a
  // ~6 mm lead). Empty: m s²/4π² from the mass and lead above.
  std::optional<double> slide_inertia_override;
  // Model 3 replaces the coupling by a length of spindle of this diameter with the
  // coupling's stiffness. The report's piece is of the 35 mm spindle, and it stays that piece
  // when its study varies only the spindle. Empty: the spindle's diameter.
  std::optional<double> coupling_piece_diameter;

  // The set as the report used it: I_slide = 2.1e-4 kg m².
  static SlideDriveData report_cnc200();

  double polar_moment() const;          // J = π d⁴/32 [m⁴]
  double spindle_inertia() const;       // I_sp = ρ J l [kg m²]
  double spindle_stiffness() const;     // C_sp = G J / l [N m/rad]
  double slide_inertia() const;         // I_slide [kg m²], see slide_inertia_override
  double metres_per_radian() const;     // s / 2π [m/rad]
  double coupling_piece_polar_moment() const;  // J of the coupling's stand-in piece [m⁴]
  // The coupling as a length of that piece with the same stiffness: l_eq = G J_piece / C_kopp [m].
  double coupling_equivalent_length() const;
};

}  // namespace mechsim::models::nc

// Torsional eigenfrequency models of the slide drive train: coupling + spindle + slide,
// free–free, without the motor (spec nc_slide.md §2, as in the report).
//
//   model 1  two inertias I1 = I_kopp + I_sp/2, I2 = I_slide + I_sp/2 joined by the series
//            spring c1 = C_kopp C_sp/(C_kopp + C_sp)                      (report: 520 Hz)
//   model 2  grounded chain  frame —C_kopp— I1 —C_sp— I2  (2×2 generalised eigenproblem)
//   model 3  continuous shaft: the coupling replaced by l_eq = G J / C_kopp of the 35 mm
//            spindle (kept when the spindle diameter is varied: then the shaft is stepped),
//            followed by the spindle (length l); the slide is a lumped inertia at
//            its position; free–free. Lowest non-rigid mode by Rayleigh–Ritz with cosines
//            (the report uses 3 shapes) or by a lumped-mass FE chain.  (report: 786 Hz, mid)
//
// Slide position convention (model 3): x is measured along the real spindle from its drive
// (coupling) end, 0 <= x <= l; on the equivalent shaft the slide sits at s = l_eq + x.
// "Mid position" is x = l/2. With N = 3 shapes this gives 783.1 Hz with the report's
// I_slide = 2.1e-4 kg m² and 785.9 Hz with m s²/4π² (5 mm lead): the report's 786 Hz.
// The middle of the equivalent shaft, s = (l_eq + l)/2, is the node of the first free–free
// mode: there the slide inertia drops out and f0 = sqrt(G/ρ)/(2(l_eq + l)) = 793.2 Hz for
// any slide inertia and any N — that is the maximum of f0(x) "near the middle", not the
// report's mid position.
//
// The coupling inertia I_kopp is not lumped in model 3 by default: the report replaces the
// coupling by shaft, whose own inertia ρ J l_eq (5.9e-4 kg m²) stands for it.
#pragma once

#include <vector>

#include "mechsim/models/nc/slide_drive_data.h"
#include "mechsim/models/nc/torsion_shaft.h"

namespace mechsim::models::nc {

// Model 1 [Hz].
double two_inertia_frequency_hz(const SlideDriveData& data);

// Model 2: both natural frequencies [Hz], ascending.
struct GroundedChainFrequencies {
  double first_hz;
  double second_hz;
};
GroundedChainFrequencies grounded_chain_frequencies_hz(const SlideDriveData& data);

// Model 3 geometry: the equivalent shaft (length l_eq + l) and its lumped inertias. Uniform
// when the coupling's piece is of the spindle's diameter, else stepped (piece, spindle).
SteppedShaft equivalent_shaft(const SlideDriveData& data);
// The data with another spindle diameter and nothing else changed: the coupling keeps its
// stand-in piece (the report's diameter study, spec nc_slide.md §2).
SlideDriveData with_spindle_diameter(const SlideDriveData& data, double diameter);
std::vector<LumpedInertia> equivalent_shaft_lumps(const SlideDriveData& data, double slide_position,
                                                  bool lump_coupling_inertia = false);
// x = l/2, see the convention above [m].
double mid_slide_position(const SlideDriveData& data);

// Model 3, lowest non-rigid mode [Hz]: Rayleigh–Ritz with ritz_shapes cosines (n = 0 included).
double continuous_shaft_frequency_hz(const SlideDriveData& data, double slide_position, int ritz_shapes = 3,
                                     bool lump_coupling_inertia = false);
// The same shaft as a lumped-mass FE chain with num_elements elements, as a check [Hz].
double continuous_shaft_fe_frequency_hz(const SlideDriveData& data, double slide_position, int num_elements,
                                        bool lump_coupling_inertia = false);

// Sweeps (report §2): model 3 against slide position, and all models against diameter.
struct PositionSweepPoint {
  double slide_position;  // x [m]
  double frequency_hz;    // model 3, Ritz
};
std::vector<PositionSweepPoint> frequency_vs_slide_position(const SlideDriveData& data,
                                                            const std::vector<double>& slide_positions,
                                                            int ritz_shapes = 3);

struct DiameterSweepPoint {
  double diameter;           // d [m]
  double model1_hz;
  double model2_first_hz;
  double model2_second_hz;
  double model3_hz;          // at the given slide position, Ritz
};
std::vector<DiameterSweepPoint> frequencies_vs_diameter(const SlideDriveData& data,
                                                        const std::vector<double>& diameters,
                                                        double slide_position, int ritz_shapes = 3);

}  // namespace mechsim::models::nc

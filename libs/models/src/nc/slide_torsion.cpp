#include "mechsim/models/nc/slide_torsion.h"

#include <cmath>
#include <stdexcept>

#include "mechsim/models/constants.h"

namespace mechsim::models::nc {

namespace {

struct TwoInertias {
  double drive_end;  // I1 = I_kopp + I_sp/2
  double slide_end;  // I2 = I_slide + I_sp/2
};

TwoInertias two_inertias(const SlideDriveData& data) {
  const double half_spindle = data.spindle_inertia() / 2;
  return {data.coupling_inertia + half_spindle, data.slide_inertia() + half_spindle};
}

}  // namespace

double two_inertia_frequency_hz(const SlideDriveData& data) {
  const auto [i1, i2] = two_inertias(data);
  const double c_kopp = data.coupling_stiffness, c_sp = data.spindle_stiffness();
  const double series = c_kopp * c_sp / (c_kopp + c_sp);
  return std::sqrt(series * (i1 + i2) / (i1 * i2)) / two_pi;
}

GroundedChainFrequencies grounded_chain_frequencies_hz(const SlideDriveData& data) {
  const auto [i1, i2] = two_inertias(data);
  const double c1 = data.coupling_stiffness, c2 = data.spindle_stiffness();
  Eigen::Matrix2d stiffness, mass;
  stiffness << c1 + c2, -c2, -c2, c2;
  mass << i1, 0, 0, i2;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> solver(stiffness, mass, Eigen::EigenvaluesOnly);
  const Eigen::Vector2d omega = solver.eigenvalues().cwiseSqrt();
  return {omega(0) / two_pi, omega(1) / two_pi};
}

SteppedShaft equivalent_shaft(const SlideDriveData& data) {
  const double polar = data.polar_moment(), piece = data.coupling_piece_polar_moment();
  if (piece == polar)  // the coupling's piece is of this spindle: one uniform shaft
    return UniformShaft{data.coupling_equivalent_length() + data.spindle_length, data.shear_modulus * polar,
                        data.density * polar};
  return SteppedShaft({{data.coupling_equivalent_length(), data.shear_modulus * piece, data.density * piece},
                       {data.spindle_length, data.shear_modulus * polar, data.density * polar}});
}

SlideDriveData with_spindle_diameter(const SlideDriveData& data, double diameter) {
  SlideDriveData varied = data;
  varied.coupling_piece_diameter = data.coupling_piece_diameter.value_or(data.spindle_diameter);
  varied.spindle_diameter = diameter;
  return varied;
}

std::vector<LumpedInertia> equivalent_shaft_lumps(const SlideDriveData& data, double slide_position,
                                                  bool lump_coupling_inertia) {
  if (slide_position < 0 || slide_position > data.spindle_length)
    throw std::invalid_argument("slide position must lie on the spindle, 0 <= x <= l");
  std::vector<LumpedInertia> lumps{{data.coupling_equivalent_length() + slide_position, data.slide_inertia()}};
  if (lump_coupling_inertia) lumps.push_back({0.0, data.coupling_inertia});
  return lumps;
}

double mid_slide_position(const SlideDriveData& data) { return data.spindle_length / 2; }

double continuous_shaft_frequency_hz(const SlideDriveData& data, double slide_position, int ritz_shapes,
                                     bool lump_coupling_inertia) {
  if (ritz_shapes < 2) throw std::invalid_argument("Ritz needs >= 2 shapes for a non-rigid mode");
  return ritz_frequencies_hz(equivalent_shaft(data),
                             equivalent_shaft_lumps(data, slide_position, lump_coupling_inertia),
                             ritz_shapes)(1);
}

double continuous_shaft_fe_frequency_hz(const SlideDriveData& data, double slide_position, int num_elements,
                                        bool lump_coupling_inertia) {
  return fe_chain_frequencies_hz(equivalent_shaft(data),
                                 equivalent_shaft_lumps(data, slide_position, lump_coupling_inertia),
                                 num_elements)(1);
}

std::vector<PositionSweepPoint> frequency_vs_slide_position(const SlideDriveData& data,
                                                            const std::vector<double>& slide_positions,
                                                            int ritz_shapes) {
  std::vector<PositionSweepPoint> sweep;
  for (double x : slide_positions) sweep.push_back({x, continuous_shaft_frequency_hz(data, x, ritz_shapes)});
  return sweep;
}

std::vector<DiameterSweepPoint> frequencies_vs_diameter(const SlideDriveData& data,
                                                        const std::vector<double>& diameters,
                                                        double slide_position, int ritz_shapes) {
  std::vector<DiameterSweepPoint> sweep;
  for (double d : diameters) {
    const SlideDriveData varied = with_spindle_diameter(data, d);
    const auto chain = grounded_chain_frequencies_hz(varied);
    sweep.push_back({d, two_inertia_frequency_hz(varied), chain.first_hz, chain.second_hz,
                     continuous_shaft_frequency_hz(varied, slide_position, ritz_shapes)});
  }
  return sweep;
}

}  // namespace mechsim::models::nc

// A shaft in torsion, free at both ends, carrying lumped inertias: the common structure
// behind the slide's continuous-shaft eigenmodel (spec nc_slide.md §2, model 3) and the
// modal slide block (§2, "modal"). The shaft is uniform or stepped (segments of their own
// rigidity and inertia: model 3 with a spindle of another diameter than the 35 mm spindle
// piece that stands in for the coupling).
//
// Two discretisations are offered so that each checks the other:
//   * Rayleigh–Ritz with the free–free cosine shapes cos(nπs/L), n = 0..N−1 (n = 0 is the
//     rigid rotation). They satisfy the natural (free) end conditions, so Ritz gives upper
//     bounds that fall monotonically with N; the kink a lumped inertia puts into the mode
//     shape makes the convergence slow (about 1/N).
//   * A lumped-mass finite-element chain (linear elements, half the element inertia at each
//     node). For a uniform shaft it converges from below, as O(h²).
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace mechsim::models::nc {

struct UniformShaft {
  double length;                  // L [m]
  double torsional_rigidity;      // G J [N m²/rad]
  double inertia_per_length;      // ρ J [kg m]
};

// Segments from s = 0 on, end to end; a uniform shaft is one segment.
struct SteppedShaft {
  std::vector<UniformShaft> segments;
  double length() const;
  SteppedShaft(std::vector<UniformShaft> s) : segments(std::move(s)) {}
  SteppedShaft(const UniformShaft& uniform) : segments{uniform} {}  // NOLINT: a uniform shaft is a stepped one
};

struct LumpedInertia {
  double position;  // s from the shaft's start, 0 <= s <= L [m]
  double inertia;   // [kg m²]
};

// Ritz shape n at s: cos(nπs/L).
double cosine_shape(int n, double s, double length);

struct RitzMatrices {
  Eigen::MatrixXd mass;       // M_mn = ∫ρJ φm φn ds + Σ I_i φm(s_i) φn(s_i)
  Eigen::MatrixXd stiffness;  // K_mn = ∫GJ φm' φn' ds (diagonal for cosines)
};
// Closed-form segment integrals; exactly diagonal for a uniform shaft.
RitzMatrices cosine_ritz_matrices(const SteppedShaft& shaft, const std::vector<LumpedInertia>& lumps,
                                  int num_shapes);

// Natural frequencies [Hz], ascending, of the Ritz model with num_shapes cosines; entry 0 is
// the rigid mode (≈ 0).
Eigen::VectorXd ritz_frequencies_hz(const SteppedShaft& shaft, const std::vector<LumpedInertia>& lumps,
                                    int num_shapes);

// Natural frequencies [Hz], ascending, of the lumped-mass chain with num_elements elements.
// The mesh puts a node on every lumped inertia and every step of the shaft: the elements are
// shared out between the pieces in proportion to their length (at least one per piece).
Eigen::VectorXd fe_chain_frequencies_hz(const SteppedShaft& shaft, const std::vector<LumpedInertia>& lumps,
                                        int num_elements);

}  // namespace mechsim::models::nc

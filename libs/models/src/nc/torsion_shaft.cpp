#include "mechsim/models/nc/torsion_shaft.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace mechsim::models::nc {

namespace {

void check_shaft(const SteppedShaft& shaft, const std::vector<LumpedInertia>& lumps) {
  if (shaft.segments.empty()) throw std::invalid_argument("SteppedShaft: no segment");
  for (const auto& seg : shaft.segments)
    if (!(seg.length > 0 && seg.torsional_rigidity > 0 && seg.inertia_per_length > 0))
      throw std::invalid_argument("UniformShaft: length, rigidity and inertia per length must be > 0");
  for (const auto& lump : lumps)
    if (lump.position < 0 || lump.position > shaft.length() || lump.inertia < 0)
      throw std::invalid_argument("LumpedInertia: position outside the shaft or negative inertia");
}

// ∫ cos(a s) cos(b s) ds and ∫ sin(a s) sin(b s) ds over [s0, s1], a = mπ/L, b = nπ/L.
double cos_cos(int m, int n, double L, double s0, double s1) {
  const double a = m * std::numbers::pi / L, b = n * std::numbers::pi / L;
  if (m == n) return m == 0 ? s1 - s0 : (s1 - s0) / 2 + (std::sin(2 * a * s1) - std::sin(2 * a * s0)) / (4 * a);
  auto f = [&](double s) { return std::sin((a - b) * s) / (2 * (a - b)) + std::sin((a + b) * s) / (2 * (a + b)); };
  return f(s1) - f(s0);
}
double sin_sin(int m, int n, double L, double s0, double s1) {
  if (m == 0 || n == 0) return 0.0;
  const double a = m * std::numbers::pi / L, b = n * std::numbers::pi / L;
  if (m == n) return (s1 - s0) / 2 - (std::sin(2 * a * s1) - std::sin(2 * a * s0)) / (4 * a);
  auto f = [&](double s) { return std::sin((a - b) * s) / (2 * (a - b)) - std::sin((a + b) * s) / (2 * (a + b)); };
  return f(s1) - f(s0);
}

Eigen::VectorXd to_hz(const Eigen::VectorXd& omega_squared) {
  // The rigid mode comes out as a tiny ± round-off; clamp it to 0.
  return omega_squared.cwiseMax(0.0).cwiseSqrt() / (2 * std::numbers::pi);
}

}  // namespace

double cosine_shape(int n, double s, double length) {
  return std::cos(n * std::numbers::pi * s / length);
}

double SteppedShaft::length() const {
  double L = 0;
  for (const auto& seg : segments) L += seg.length;
  return L;
}

RitzMatrices cosine_ritz_matrices(const SteppedShaft& shaft, const std::vector<LumpedInertia>& lumps,
                                  int num_shapes) {
  check_shaft(shaft, lumps);
  if (num_shapes < 1) throw std::invalid_argument("cosine_ritz_matrices: num_shapes must be >= 1");
  const double L = shaft.length();
  RitzMatrices r{Eigen::MatrixXd::Zero(num_shapes, num_shapes), Eigen::MatrixXd::Zero(num_shapes, num_shapes)};
  if (shaft.segments.size() == 1) {
    // The cosines are orthogonal on [0, L]: ∫cos² = L (n = 0) or L/2; ∫(φn')² = (nπ/L)² L/2.
    const UniformShaft& u = shaft.segments.front();
    for (int n = 0; n < num_shapes; ++n) {
      r.mass(n, n) = u.inertia_per_length * (n == 0 ? L : L / 2);
      const double wave_number = n * std::numbers::pi / L;
      r.stiffness(n, n) = u.torsional_rigidity * wave_number * wave_number * L / 2;
    }
  } else {
    // Piecewise constant ρJ and GJ: the segment integrals couple the cosines.
    double s0 = 0;
    for (const auto& seg : shaft.segments) {
      const double s1 = s0 + seg.length;
      for (int m = 0; m < num_shapes; ++m)
        for (int n = 0; n < num_shapes; ++n) {
          r.mass(m, n) += seg.inertia_per_length * cos_cos(m, n, L, s0, s1);
          r.stiffness(m, n) += seg.torsional_rigidity * (m * std::numbers::pi / L) * (n * std::numbers::pi / L) *
                               sin_sin(m, n, L, s0, s1);
        }
      s0 = s1;
    }
  }
  for (const auto& lump : lumps) {
    Eigen::VectorXd phi(num_shapes);
    for (int n = 0; n < num_shapes; ++n) phi(n) = cosine_shape(n, lump.position, L);
    r.mass += lump.inertia * phi * phi.transpose();
  }
  return r;
}

Eigen::VectorXd ritz_frequencies_hz(const SteppedShaft& shaft, const std::vector<LumpedInertia>& lumps,
                                    int num_shapes) {
  const RitzMatrices r = cosine_ritz_matrices(shaft, lumps, num_shapes);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(r.stiffness, r.mass,
                                                                    Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success) throw std::runtime_error("ritz_frequencies_hz: eigensolver failed");
  return to_hz(solver.eigenvalues());
}

Eigen::VectorXd fe_chain_frequencies_hz(const SteppedShaft& shaft, const std::vector<LumpedInertia>& lumps,
                                        int num_elements) {
  check_shaft(shaft, lumps);
  const double L = shaft.length();
  // Piece boundaries: the shaft ends, its steps and every lump (closer than 1e-12 L merge).
  std::vector<double> breaks{0.0, L};
  for (double s = 0; const auto& seg : shaft.segments) breaks.push_back(s += seg.length);
  for (const auto& lump : lumps) breaks.push_back(lump.position);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end(),
                           [L](double a, double b) { return std::abs(a - b) <= 1e-12 * L; }),
               breaks.end());
  const int num_segments = static_cast<int>(breaks.size()) - 1;
  if (num_elements < num_segments)
    throw std::invalid_argument("fe_chain_frequencies_hz: need at least one element between lumps");

  // One element per segment, the rest by largest remainder in proportion to segment length.
  std::vector<int> count(num_segments, 1);
  std::vector<std::pair<double, int>> remainder;
  int spare = num_elements - num_segments;
  int given = 0;
  for (int i = 0; i < num_segments; ++i) {
    const double share = spare * (breaks[i + 1] - breaks[i]) / L;
    const int whole = static_cast<int>(std::floor(share));
    count[i] += whole;
    given += whole;
    remainder.push_back({share - whole, i});
  }
  std::sort(remainder.rbegin(), remainder.rend());
  for (int j = 0; j < spare - given; ++j) ++count[remainder[j].second];

  // Nodes, lumped node inertias and element stiffnesses.
  std::vector<double> node_position{0.0}, element_stiffness;
  std::vector<double> node_inertia{0.0};
  for (int i = 0; i < num_segments; ++i) {
    const double h = (breaks[i + 1] - breaks[i]) / count[i];
    // The shaft segment this piece lies in (pieces never straddle a step).
    const double middle = (breaks[i] + breaks[i + 1]) / 2;
    const UniformShaft* seg = &shaft.segments.back();
    for (double s = 0; const auto& candidate : shaft.segments)
      if (middle < (s += candidate.length)) {
        seg = &candidate;
        break;
      }
    for (int e = 0; e < count[i]; ++e) {
      const double half = seg->inertia_per_length * h / 2;
      node_inertia.back() += half;
      node_inertia.push_back(half);
      node_position.push_back(breaks[i] + (e + 1) * h);
      element_stiffness.push_back(seg->torsional_rigidity / h);
    }
  }
  for (const auto& lump : lumps) {
    auto it = std::min_element(node_position.begin(), node_position.end(), [&](double a, double b) {
      return std::abs(a - lump.position) < std::abs(b - lump.position);
    });
    node_inertia[it - node_position.begin()] += lump.inertia;
  }

  // M^(-1/2) K M^(-1/2) is symmetric tridiagonal: solve it as such (O(n²), fine for n ~ 1e3).
  const int n = static_cast<int>(node_inertia.size());
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(n), sub_diagonal(n - 1);
  for (int e = 0; e < n - 1; ++e) {
    diagonal(e) += element_stiffness[e] / node_inertia[e];
    diagonal(e + 1) += element_stiffness[e] / node_inertia[e + 1];
    sub_diagonal(e) = -element_stiffness[e] / std::sqrt(node_inertia[e] * node_inertia[e + 1]);
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver;
  solver.computeFromTridiagonal(diagonal, sub_diagonal, Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success) throw std::runtime_error("fe_chain_frequencies_hz: eigensolver failed");
  return to_hz(solver.eigenvalues());
}

}  // namespace mechsim::models::nc

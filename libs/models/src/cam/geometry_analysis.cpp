#include "mechsim/models/cam/geometry_analysis.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "mechsim/models/constants.h"
#include "numerics.h"

namespace mechsim::models::cam {

namespace {

// Coarse sampling before refinement: fine enough to separate neighbouring extrema of
// the smooth α(θ) and κ(θ) of real laws.
constexpr double sample_step_rad = 0.05 * std::numbers::pi / 180.0;

int samples_for(double width) { return std::max(4, static_cast<int>(std::ceil(width / sample_step_rad))); }

using numerics::wrap;

}  // namespace

PressureAngleExtremes pressure_angle_extremes(const MotionLaw& law, double pitch_radius_m,
                                              double eccentricity_m) {
  PressureAngleExtremes out{{0.0, -inf}, {0.0, inf}};
  const auto& pieces = law.pieces();
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const double a = pieces[i].segment.start_rad, b = a + pieces[i].segment.span_rad;
    auto alpha = [&](double t) {
      const LawPoint p = law.evaluate_piece(i, t);
      return pressure_angle(p.s, p.s_d1, pitch_radius_m, eccentricity_m);
    };
    const auto hi = numerics::maximise(alpha, a, b, samples_for(b - a));
    const auto lo = numerics::minimise(alpha, a, b, samples_for(b - a));
    if (hi.value > out.max.value) out.max = {wrap(hi.x), hi.value};
    if (lo.value < out.min.value) out.min = {wrap(lo.x), lo.value};
  }
  return out;
}

CurvatureAnalysis curvature_analysis(const MotionLaw& law, const CamGeometry& g) {
  CurvatureAnalysis out{{}, inf, 0.0, inf, false};
  const auto& pieces = law.pieces();
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const double a = pieces[i].segment.start_rad, b = a + pieces[i].segment.span_rad;
    auto kappa = [&](double t) {
      const LawPoint p = law.evaluate_piece(i, t);
      return pitch_curvature(p.s, p.s_d1, p.s_d2, g.pitch_radius_m, g.eccentricity_m);
    };
    // The smallest convex radius is the largest positive curvature, the smallest concave
    // |ρ| the most negative curvature.
    const auto most_convex = numerics::maximise(kappa, a, b, samples_for(b - a));
    const auto most_concave = numerics::minimise(kappa, a, b, samples_for(b - a));
    PieceCurvature pc{i, pieces[i].segment, pieces[i].filler, most_convex.value > 0.0, inf, 0.0,
                      most_concave.value < 0.0, inf, 0.0};
    if (pc.has_convex) {
      pc.min_positive_rho_m = 1.0 / most_convex.value;
      pc.angle_min_positive_rad = wrap(most_convex.x);
      if (pc.min_positive_rho_m < out.min_positive_rho_m) {
        out.min_positive_rho_m = pc.min_positive_rho_m;
        out.angle_min_positive_rad = pc.angle_min_positive_rad;
      }
    }
    if (pc.has_concave) {
      pc.min_concave_abs_rho_m = -1.0 / most_concave.value;
      pc.angle_min_concave_rad = wrap(most_concave.x);
    }
    out.pieces.push_back(pc);
  }
  out.min_contour_rho_m = out.min_positive_rho_m - g.roller_radius_m;
  out.undercut = out.min_positive_rho_m < g.roller_radius_m;
  return out;
}

OptimalEccentricity optimal_eccentricity(const MotionLaw& law, double pitch_radius_m) {
  auto imbalance = [&](double e) {
    const PressureAngleExtremes x = pressure_angle_extremes(law, pitch_radius_m, e);
    return std::abs(x.max.value) - std::abs(x.min.value);
  };
  double lo = -0.5 * pitch_radius_m, hi = 0.5 * pitch_radius_m;
  double e;
  if (imbalance(lo) >= 0.0 && imbalance(hi) <= 0.0) {
    e = numerics::bisect(imbalance, lo, hi);
  } else {
    // No balance within the range (a law that only rises, say): the least imbalance.
    e = numerics::minimise([&](double x) { return std::abs(imbalance(x)); }, lo, hi, 200).x;
  }
  return {e, pressure_angle_extremes(law, pitch_radius_m, e)};
}

std::vector<ContourSample> sample_contour(const MotionLaw& law, const CamGeometry& g, int count) {
  if (count < 3) throw std::invalid_argument("sample_contour: need at least 3 samples");
  std::vector<ContourSample> out;
  out.reserve(count);
  for (int i = 0; i < count; ++i) {
    const double th = two_pi * i / count;
    const LawPoint p = law.evaluate(th);
    const double rho = pitch_curvature_radius(p.s, p.s_d1, p.s_d2, g.pitch_radius_m, g.eccentricity_m);
    out.push_back({th, p.s, pressure_angle(p.s, p.s_d1, g.pitch_radius_m, g.eccentricity_m), rho,
                   rho - g.roller_radius_m, pitch_contour_point(th, p.s, g.pitch_radius_m, g.eccentricity_m),
                   cam_contour_point(th, p.s, p.s_d1, g.pitch_radius_m, g.eccentricity_m, g.roller_radius_m)});
  }
  return out;
}

}  // namespace mechsim::models::cam

#include "bench_runner.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace mechsim::bench {

double fit_order(const std::vector<double>& h, const std::vector<double>& error) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < h.size() && i < error.size(); ++i) {
    if (!(error[i] > 0) || !std::isfinite(error[i]) || !(h[i] > 0)) continue;
    const double x = std::log(h[i]), y = std::log(error[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++n;
  }
  if (n < 3) return kNaN;
  const double d = n * sxx - sx * sx;
  return d > 0 ? (n * sxy - sx * sy) / d : kNaN;
}

double envelope_at(const std::vector<std::pair<double, double>>& points, double wall, int* lo, int* hi) {
  std::vector<int> idx;
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    const auto& [w, e] = points[i];
    if (w > 0 && std::isfinite(w) && e > 0 && std::isfinite(e)) idx.push_back(i);
  }
  if (lo) *lo = -1;
  if (hi) *hi = -1;
  if (idx.empty() || !(wall > 0)) return kNaN;
  std::sort(idx.begin(), idx.end(), [&](int a, int b) {
    return points[a].first != points[b].first ? points[a].first < points[b].first : points[a].second < points[b].second;
  });
  if (wall < points[idx.front()].first || wall > points[idx.back()].first) return kNaN;
  // The corners: each point with a smaller error than every faster one.
  std::vector<int> corners;
  for (int i : idx)
    if (corners.empty() || points[i].second < points[corners.back()].second) corners.push_back(i);
  std::size_t k = 0;
  while (k + 1 < corners.size() && points[corners[k + 1]].first <= wall) ++k;
  const int a = corners[k];
  if (k + 1 == corners.size() || points[a].first == wall) {
    if (lo) *lo = a;
    if (hi) *hi = a;
    return points[a].second;
  }
  const int b = corners[k + 1];
  const double x0 = std::log(points[a].first), x1 = std::log(points[b].first);
  const double y0 = std::log(points[a].second), y1 = std::log(points[b].second);
  if (lo) *lo = a;
  if (hi) *hi = b;
  return std::exp(y0 + (y1 - y0) * (std::log(wall) - x0) / (x1 - x0));
}

// The tightest node tolerance swept (the observed orders are fitted there).
double Bench::tightest_rtol() const {
  double tight = opt_.rtol;
  for (double rt : rtols_) tight = std::min(tight, rt);
  return tight;
}

// Observed order per scheme: cvode_bdf at the tightest tolerance swept, over the points
// that are neither saturated by the tolerance/reference floor nor outside the asymptotic
// range (docs/accuracy.md).
json Bench::observed_orders() {
  json orders = json::array();
  const double tight = tightest_rtol();
  for (int v = 0; v < static_cast<int>(variants_.size()); ++v) {
    std::vector<double> hs, es;
    json used = json::array();
    for (std::size_t i = 0; i < specs_.size(); ++i) {
      const auto& r = specs_[i];
      if (r.variant != v || r.solver != "cvode_bdf" || r.rtol != tight) continue;
      const auto& res = results_[i];
      if (res.status != "ok" || !std::isfinite(res.rms_rel)) continue;
      double floor_rel = 0;
      const Reference& ref = reference(v, r.h);
      for (auto& [name, e] : ref.accuracy_json["signals"].items())
        floor_rel = std::max(floor_rel, e.value("rms_rel_difference", 0.0));
      floor_rel = std::max(floor_rel, r.rtol);
      if (res.rms_rel < 10 * floor_rel || res.rms_rel > 0.1) continue;
      hs.push_back(r.h);
      es.push_back(res.rms_rel);
      used.push_back(r.h);
    }
    const double p = fit_order(hs, es);
    orders.push_back({{"scheme", variants_[v].name},
                      {"solver", "cvode_bdf"},
                      {"rtol", tight},
                      {"order", finite_or_null(p)},
                      {"steps_used_s", used},
                      {"note", std::isfinite(p) ? "" : "fewer than 3 non-saturated stable points"}});
  }
  return orders;
}

// Best scheme against zero-order-hold Jacobi: the largest factor e_zoh / e over pairs of
// runs where the other run took no more wall time than the zero-order-hold one. Sets
// best_scheme_ (the plots keep it).
json Bench::best_vs_zero_order_hold() {
  json ten_x = json::object();
  std::vector<std::pair<double, double>> zoh;
  for (std::size_t i = 0; i < specs_.size(); ++i)
    if (variants_[specs_[i].variant].zero_order_hold_jacobi && results_[i].status == "ok" && std::isfinite(results_[i].rms_rel))
      zoh.push_back({results_[i].wall_time_s, results_[i].rms_rel});
  double best = 0;
  json where;
  bool any_other_ok = false;
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    if (variants_[specs_[i].variant].zero_order_hold_jacobi || results_[i].status != "ok") continue;
    any_other_ok = true;
    // A refused (below reference accuracy) error is bounded by the reference's error.
    const double e = std::isfinite(results_[i].rms_rel) ? results_[i].rms_rel : results_[i].rms_rel_bound;
    if (!(e > 0)) continue;
    for (const auto& [wz, ez] : zoh)
      if (results_[i].wall_time_s <= wz && ez / e > best) {
        best = ez / e;
        where = {{"scheme", variants_[specs_[i].variant].name}, {"solver", specs_[i].solver}, {"rtol", specs_[i].rtol},
                 {"step_s", specs_[i].h}, {"wall_time_s", results_[i].wall_time_s}, {"rms_rel", e},
                 {"bounded_by_reference", !std::isfinite(results_[i].rms_rel)}, {"zoh_wall_time_s", wz}, {"zoh_rms_rel", ez}};
      }
  }
  ten_x["definition"] = "max over run pairs of rms_rel(zero-order-hold Jacobi) / rms_rel(other) where the other run's wall time <= the zero-order-hold run's";
  ten_x["zoh_stable_points"] = zoh.size();
  bool zoh_swept = false;
  for (const auto& v : variants_) zoh_swept = zoh_swept || v.zero_order_hold_jacobi;
  if (!zoh_swept) {
    ten_x["factor"] = nullptr;
    ten_x["met"] = nullptr;
    ten_x["note"] = "zero-order-hold Jacobi not swept (--schemes)";
  } else if (zoh.empty()) {
    ten_x["factor"] = nullptr;
    ten_x["met"] = any_other_ok;
    ten_x["note"] = any_other_ok ? "zero-order-hold Jacobi is unstable at every swept H; other schemes are not"
                                 : "no stable run";
  } else if (!(best > 0)) {
    ten_x["factor"] = nullptr;
    ten_x["met"] = nullptr;
    ten_x["note"] = "no other run with a measurable error at no more wall time than a zero-order-hold run";
  } else {
    ten_x["factor"] = best;
    ten_x["met"] = best >= 10;
    ten_x["at"] = where;
    if (where.is_object()) best_scheme_ = where["scheme"].get<std::string>();
  }
  return ten_x;
}

}  // namespace mechsim::bench

#include "cvt_map.h"

#include <cmath>

#include "mechsim/models/constants.h"

namespace mechsim::tools::cvt_map {

using config::ConfigNode;
namespace dim = config::dim;
namespace cvt = models::cvt;

namespace {

using models::rpm;

std::vector<double> linspace(double a, double b, int n) {
  std::vector<double> v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) v[static_cast<std::size_t>(i)] = n == 1 ? a : a + (b - a) * i / (n - 1);
  return v;
}

// An axis: {from, to, points} or a list of quantities, strictly increasing.
std::vector<double> parse_axis(const std::optional<ConfigNode>& node, config::Dimension d, std::vector<double> fallback,
                               bool zero_allowed) {
  if (!node) return fallback;
  std::vector<double> v;
  if (node->is_sequence()) {
    if (node->size() == 0) node->fail("expected a non-empty list of values or {from, to, points}");
    for (std::size_t i = 0; i < node->size(); ++i) v.push_back(node->at(i).as_quantity(d));
  } else if (node->is_map()) {
    node->allow_only({"from", "to", "points"});
    const double from = node->quantity("from", d), to = node->quantity("to", d);
    const long n = node->integer_or("points", 5);
    if (n < 1 || n > 201) node->child("points").fail("expected a number of points in 1..201");
    if (n > 1 && !(to > from)) node->child("to").fail("expected to > from");
    v = linspace(from, to, static_cast<int>(n));
  } else {
    node->fail("expected a list of values or {from, to, points}");
  }
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!(zero_allowed ? v[i] >= 0.0 : v[i] > 0.0))
      node->fail(zero_allowed ? "expected values >= 0 (the map is for positive torque and speed)" : "expected values > 0");
    if (i > 0 && !(v[i] > v[i - 1])) node->fail("expected strictly increasing values");
  }
  return v;
}

void resample(std::vector<double>& axis, const std::optional<int>& points, const char* option) {
  if (!points) return;
  if (*points < 1 || *points > 201) throw std::invalid_argument(std::string(option) + ": expected 1..201 points");
  axis = *points == 1 ? std::vector<double>{axis.front()} : linspace(axis.front(), axis.back(), *points);
}

}  // namespace

CvtMapResult analyse_scene(const config::Scene& scene, const std::vector<std::string>& overrides,
                           const GridOptions& grid) {
  CvtMapResult r;
  r.scene_name = scene.name;
  r.scene_file = scene.file;
  r.overrides = overrides;
  const config::ParticipantSpec* found = nullptr;
  int count = 0;
  for (const auto& p : scene.participants) {
    if (p.type != "cvt") continue;
    if (!found) found = &p;
    ++count;
  }
  if (found) {
    r.config = cosim::parse_cvt_config(found->params, cosim::cvt_time_run_keys());
    r.source = found->key_path + ".params";
    if (count > 1)
      r.notes.push_back(std::to_string(count) + " cvt participants: the first ('" + found->name + "') is mapped");
  } else {
    r.source = "defaults";
    r.notes.push_back("no cvt participant: the thesis rig's parameters (spec cvt.md §6.1)");
  }
  std::optional<ConfigNode> settings;
  if (scene.design && scene.design->is_map()) settings = scene.design->optional_child("cvt_map");
  if (settings) settings->allow_only({"ratio_setting", "torque", "speed"});
  auto child = [&](const char* key) { return settings ? settings->optional_child(key) : std::optional<ConfigNode>{}; };
  r.s = parse_axis(child("ratio_setting"), dim::length, linspace(5e-3, 55e-3, 5), false);
  r.torque = parse_axis(child("torque"), dim::torque, linspace(20.0, 120.0, 5), true);
  r.speed = parse_axis(child("speed"), dim::angular_velocity, linspace(1000 * rpm, 5000 * rpm, 5), true);
  resample(r.s, grid.s_points, "--s-points");
  resample(r.torque, grid.torque_points, "--torque-points");
  resample(r.speed, grid.speed_points, "--speed-points");

  cvt::CvtModel model(r.config.params);
  r.curvatures = model.curvatures();
  const std::size_t n = r.s.size() * r.torque.size() * r.speed.size();
  r.l1.resize(n);
  r.l0.resize(n);
  for (std::size_t is = 0; is < r.s.size(); ++is)
    for (std::size_t it = 0; it < r.torque.size(); ++it)
      for (std::size_t in = 0; in < r.speed.size(); ++in) {
        cvt::CvtOperatingPoint op;
        op.s = r.s[is];
        op.torque = r.torque[it];
        op.omega_C = r.speed[in];
        op.clamp = r.config.clamp;
        op.v_K = r.config.safety_factor;
        op.F_K_applied = r.config.clamping_force;
        const std::size_t k = r.index(is, it, in);
        try {
          op.level = cvt::Level::L1;
          r.l1[k] = model.evaluate(op);
          op.level = cvt::Level::L0;
          r.l0[k] = model.evaluate(op);
        } catch (const cvt::CvtInputError& e) {
          // A ratio setting outside the geometric range: refuse the whole map, naming it.
          const std::string where = settings ? settings->path() : r.source;
          throw config::ConfigError(scene.file, where, e.what());
        }
      }
  return r;
}

}  // namespace mechsim::tools::cvt_map

#include "mechsim/cosim/step_control.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mechsim::cosim {

namespace {

constexpr double kSafety = 0.8;     // aim below the tolerance: no step is ever redone
constexpr double kMaxGrowth = 2.0;   // per step; the estimate acts a step late
constexpr double kMaxShrink = 0.2;

int error_order(config::EdgeOrder order, config::Reconstruction r) {
  if (order == config::EdgeOrder::gauss_seidel) return 2;
  switch (r) {
    case config::Reconstruction::hold: return 1;
    case config::Reconstruction::linear: return 2;
    case config::Reconstruction::quadratic: return 3;
  }
  return 1;
}

// The reconstruction's error over a step of length h, per unit of the signal's derivative
// of order q (the leading term of the interpolation remainder, without its 1/q!): the
// distances from the reconstructed instant to the q samples it uses. A Jacobi edge
// extrapolates from t_k over h with the samples at t_k, t_k - s1, t_k - s2 (hold: h; linear:
// h (h + s1); quadratic: h (h + s1) (h + s2)); on unequal steps this is what makes the error
// of a step depend on the step before it as well.
double reach_product(double h, int q, const double* s) {
  double p = h;
  for (int i = 1; i < q; ++i) p *= h + s[i - 1];
  return p;
}

// The longest h with (k1 + dk h / 2) w reach_product(h, q, s) <= target (k1, dk >= 0,
// offsets s >= 0). The left side is increasing and convex in h, so Newton's method from a
// bound at or beyond the root comes down on the root from above and never overshoots it:
// a fixed count of iterations, the same doubles on every node. The bounds: h + s_i >= h
// (the power alone), and h + s_i >= s_i (nearly linear where the offsets dominate).
double longest_within(double k1, double dk, int q, const double* s, double w, double target) {
  const double c = dk / 2;
  const double inf = std::numeric_limits<double>::infinity();
  if (!(k1 > 0) && !(c > 0)) return inf;
  target /= w;
  double offsets = 1.0;
  for (int i = 1; i < q; ++i) offsets *= s[i - 1];
  double h = inf;
  if (k1 > 0) {
    h = std::min(h, std::pow(target / k1, 1.0 / q));
    if (offsets > 0) h = std::min(h, target / (k1 * offsets));
  }
  if (c > 0) {
    h = std::min(h, std::pow(target / c, 1.0 / (q + 1)));
    if (offsets > 0) h = std::min(h, std::sqrt(target / (c * offsets)));
  }
  for (int i = 0; i < 12; ++i) {
    // f = (k1 + c h) P(h), f' = c P + (k1 + c h) P', P' = P sum 1 / (h + s_i).
    const double p = reach_product(h, q, s);
    double dlogp = 1.0 / h;
    for (int j = 1; j < q; ++j) dlogp += 1.0 / (h + s[j - 1]);
    const double g = (k1 + c * h) * p - target;
    const double slope = c * p + (k1 + c * h) * p * dlogp;
    if (!(g > 0) || !(slope > 0)) break;
    h -= g / slope;
  }
  return h;
}

}  // namespace

void CouplingErrorEstimate::Channel::widen(std::span<const double> v, std::size_t offset) {
  if (lo.size() < offset + v.size()) {
    lo.resize(offset + v.size(), std::numeric_limits<double>::infinity());
    hi.resize(offset + v.size(), -std::numeric_limits<double>::infinity());
  }
  for (std::size_t f = 0; f < v.size(); ++f)
    if (std::isfinite(v[f])) {
      lo[offset + f] = std::min(lo[offset + f], v[f]);
      hi[offset + f] = std::max(hi[offset + f], v[f]);
    }
}

double CouplingErrorEstimate::Channel::scale(std::size_t entry) const {
  const double least = entry < least_scale.size() ? least_scale[entry] : 0.0;
  if (entry >= lo.size() || !(hi[entry] >= lo[entry])) return least;
  return std::max(least, std::max(hi[entry] - lo[entry], std::max(std::abs(lo[entry]), std::abs(hi[entry]))));
}

double CouplingErrorEstimate::Channel::instant(std::uint64_t k) const {
  for (const auto& [step, t] : instants)
    if (step == k) return t;
  return std::numeric_limits<double>::quiet_NaN();
}

void CouplingErrorEstimate::Channel::measured(std::uint64_t k, std::span<const double> difference) {
  // A reconstruction that reaches back across the last event measures the jump, not the
  // signal: no estimate until the samples it uses all lie after it.
  const double a = instant(k) - instant(k - 1);
  if (k < last_event + static_cast<std::uint64_t>(reaches_back) || !(a > 0)) {
    last.reset();
    before.reset();
    older.reset();
    return;
  }
  // The reach: the distances from t_k to the samples the reconstruction used (Gauss-Seidel:
  // the line through the two samples before t_k, as a linear extrapolation), a (a + back[0])
  // (a + back[1]) with back[i - 1] the distance from t_k-1 to the sample i steps before it.
  // (t_0 is never passed in: taken as a step of the same length, as on equal steps.)
  double back[2] = {0.0, 0.0};
  for (int i = 1; i < error_order; ++i) {
    const double d = instant(k - 1) - instant(k - 1 - static_cast<std::uint64_t>(i));
    back[i - 1] = d > 0 ? d : i * a;
  }
  const double a_q = reach_product(a, error_order, back);
  Measured m{k, a, std::vector<double>(topic_size + outputs.size(), 0.0), a_q};
  const auto entry = [&](std::size_t e) {
    const double s = scale(e);
    if (e < difference.size() && s > 0 && std::isfinite(difference[e])) m.k[e] = difference[e] / s / a_q;
  };
  for (std::size_t f : fields)
    if (f < topic_size) entry(f);
  for (std::size_t j = 0; j < outputs.size(); ++j) entry(topic_size + j);
  older = std::move(before);
  before = std::move(last);
  last = std::move(m);
}

CouplingErrorEstimate::CouplingErrorEstimate(std::vector<Edge> edges) {
  for (auto& edge : edges) {
    Channel c;
    c.order = edge.order;
    c.error_order = error_order(edge.order, edge.reconstruction);
    // Gauss-Seidel: the line through the two samples before t_k; Jacobi: hold 1, linear 2,
    // quadratic 3 samples before t_k.
    c.reaches_back = edge.order == config::EdgeOrder::gauss_seidel ? 2 : c.error_order;
    c.fields = std::move(edge.fields);
    // The topic's fields come first in K (their count from the scales, or the fields used).
    c.topic_size = edge.scales.size();
    for (std::size_t f : c.fields) c.topic_size = std::max(c.topic_size, f + 1);
    c.outputs = std::move(edge.outputs);
    c.least_scale = std::move(edge.scales);
    c.least_scale.resize(c.topic_size + c.outputs.size(), 0.0);
    for (std::size_t j = 0; j < c.outputs.size() && j < edge.output_scales.size(); ++j)
      c.least_scale[c.topic_size + j] = edge.output_scales[j];
    channels_.push_back(std::move(c));
  }
}

void CouplingErrorEstimate::used_at_step_end(std::size_t edge, std::uint64_t k, double t_k, std::span<const double> values,
                                             bool event) {
  Channel& c = channels_.at(edge);
  c.widen(values.first(std::min(values.size(), c.topic_size)));
  if (!c.instants.empty() && k != c.instants.back().first + 1) {  // not consecutive (a restore)
    c.instants.clear();
    c.history.clear();
    c.last.reset();
    c.before.reset();
    c.older.reset();
  }
  if (c.instants.size() == 4) c.instants.erase(c.instants.begin());
  c.instants.emplace_back(k, t_k);
  if (event) c.last_event = k;
  if (c.order == config::EdgeOrder::jacobi) {
    c.used_step = k;
    c.used.assign(values.begin(), values.end());
    return;
  }
  if (c.history.size() == 3) c.history.erase(c.history.begin());
  c.history.emplace_back(values.begin(), values.end());
  if (c.history.size() < 3) return;
  const double r = (c.instant(k) - c.instant(k - 1)) / (c.instant(k - 1) - c.instant(k - 2));
  const auto& v0 = c.history[0];
  const auto& v1 = c.history[1];
  const auto& v2 = c.history[2];
  std::vector<double> d(v2.size(), 0.0);
  for (std::size_t f = 0; f < d.size(); ++f) d[f] = v2[f] - (v1[f] + (v1[f] - v0[f]) * r);
  c.measured(k, d);
}

void CouplingErrorEstimate::received(std::size_t edge, std::uint64_t k, std::span<const double> values,
                                     std::span<const double> outputs, std::span<const double> output_change) {
  Channel& c = channels_.at(edge);
  if (c.order != config::EdgeOrder::jacobi) return;
  c.widen(values.first(std::min(values.size(), c.topic_size)));
  if (c.used_step != k || c.used.size() != values.size()) return;
  std::vector<double> d(c.topic_size + c.outputs.size(), 0.0);
  for (std::size_t f = 0; f < values.size() && f < c.topic_size; ++f) d[f] = values[f] - c.used[f];
  if (!output_change.empty()) {
    std::vector<double> watched(c.outputs.size(), 0.0);
    for (std::size_t j = 0; j < c.outputs.size(); ++j) {
      watched[j] = c.outputs[j] < outputs.size() ? outputs[c.outputs[j]] : 0.0;
      if (j < output_change.size()) d[c.topic_size + j] = output_change[j];
    }
    c.widen(watched, c.topic_size);
  }
  c.measured(k, d);
}

void CouplingErrorEstimate::discontinuity_at(std::uint64_t k) {
  for (Channel& c : channels_) {
    c.last_event = std::max(c.last_event, k);
    c.last.reset();
    c.before.reset();
    c.older.reset();
  }
}

std::optional<CouplingErrorEstimate::Result> CouplingErrorEstimate::at(std::uint64_t k, double tolerance,
                                                                     double current_h) const {
  std::optional<Result> out;
  for (const Channel& c : channels_) {
    if (!c.last || c.last->step != k) continue;
    const Measured& m = *c.last;
    const int q = c.error_order;
    // K's trend over the two steps before (the three measured last, midpoint to midpoint),
    // or over one where only two are there. Over two it does not follow a step-to-step
    // wobble (a long step measures K a little differently from a short one), which over one
    // step made the trend flip sign every step and the steps alternate long and short.
    const Measured* from = nullptr;
    double span = 0.0;
    if (c.before && c.before->step + 1 == k) {
      from = &*c.before;
      span = (m.length + c.before->length) / 2;
      if (c.older && c.older->step + 2 == k) {
        from = &*c.older;
        span = m.length / 2 + c.before->length + c.older->length / 2;
      }
    }
    const double target = kSafety * tolerance;
    double ratio = 0.0;
    double longest = std::numeric_limits<double>::infinity();
    // The proposed step starts at t_k+1 = t_k + current_h. A Jacobi edge extrapolates over it
    // from the samples at t_k+1, t_k and t_k-1; a Gauss-Seidel edge interpolates inside it, so
    // its error does not depend on the steps before (2 h^2: equal steps' h (h + h)).
    const bool jacobi = c.order == config::EdgeOrder::jacobi;
    const double s[2] = {jacobi ? current_h : 0.0, jacobi ? current_h + m.length : 0.0};
    const double w = jacobi ? 1.0 : 2.0;
    const auto entry = [&](std::size_t e) {
      if (e >= m.k.size()) return;
      ratio = std::max(ratio, std::abs(m.k[e]) * m.reach / tolerance);
      // K per unit time between the two steps' midpoints, carried to the next step's start.
      const double dk = from && e < from->k.size() ? (m.k[e] - from->k[e]) / span : 0.0;
      const double k1 = m.k[e] + dk * (m.length / 2 + current_h);
      longest = std::min(longest, longest_within(std::abs(k1), std::abs(dk), q, s, w, target));
    };
    for (std::size_t f : c.fields) entry(f);
    for (std::size_t j = 0; j < c.outputs.size(); ++j) entry(c.topic_size + j);
    if (!out) {
      out = Result{ratio, q, longest};
      continue;
    }
    out->ratio = std::max(out->ratio, ratio);
    if (longest < out->longest) {
      out->longest = longest;
      out->order = q;
    }
  }
  return out;
}

StepProposal propose_step(const config::AdaptiveStepSpec& spec, double current_h,
                          const std::optional<CouplingErrorEstimate::Result>& estimate) {
  StepProposal p;
  p.error_estimate = std::numeric_limits<double>::quiet_NaN();
  double h = current_h > 0 ? current_h : spec.initial;
  if (estimate && current_h > 0) {
    p.error_estimate = estimate->ratio;
    // A bounded change of the step under way: the estimate acts a step late.
    h = std::clamp(estimate->longest, current_h * kMaxShrink, current_h * kMaxGrowth);
  }
  p.step_length = std::clamp(h, spec.min, spec.max);
  return p;
}

bool StepAgreement::add(std::size_t participant, std::uint64_t k, const StepProposal& p) {
  auto& step = by_step_[k];
  const auto [it, added] = step.emplace(participant, p);
  return added || it->second == p;
}

bool StepAgreement::complete(std::uint64_t k) const {
  const auto it = by_step_.find(k);
  return it != by_step_.end() && it->second.size() >= participants_;
}

std::vector<std::size_t> StepAgreement::missing(std::uint64_t k) const {
  std::vector<std::size_t> out;
  const auto it = by_step_.find(k);
  for (std::size_t i = 0; i < participants_; ++i)
    if (it == by_step_.end() || !it->second.count(i)) out.push_back(i);
  return out;
}

AgreedStep end_of_step(double t_k, double h, double limit, bool limit_is_event, const config::AdaptiveStepSpec& spec,
                       double end) {
  AgreedStep out{t_k + h, false};
  // An instant less than the smallest step beyond the controller's choice is landed on (the
  // step stretches by less than `min`) rather than left for a sliver of a step.
  if (limit > t_k && limit < out.t_next + spec.min) out = {limit, limit_is_event};
  // Likewise the end: no sliver before it.
  if (out.t_next > end - spec.min) out = {end, false};
  return out;
}

AgreedStep StepAgreement::agreed(std::uint64_t k, double t) const {
  const auto& proposals = by_step_.at(k);
  double h = std::numeric_limits<double>::infinity();
  double limit = std::numeric_limits<double>::infinity();
  for (const auto& [participant, p] : proposals) {
    h = std::min(h, p.step_length);
    if (p.event_time > t) limit = std::min(limit, p.event_time);
  }
  // The limit is an event when any proposal calls it one.
  bool event = false;
  bool state_event = false;
  for (const auto& [participant, p] : proposals) {
    event = event || (p.event && p.event_time == limit);
    state_event = state_event || std::isfinite(p.state_event_time);
  }
  // A state event inside the step before: what follows it is new, as after an event.
  if (state_event) h = std::min(h, spec_.initial);
  AgreedStep a = end_of_step(t, h, limit, event, spec_, end_);
  a.after_state_event = state_event;
  return a;
}

void StepAgreement::discard_before(std::uint64_t k) {
  by_step_.erase(by_step_.begin(), by_step_.lower_bound(k));
}

}  // namespace mechsim::cosim

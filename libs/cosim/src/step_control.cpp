#include "mechsim/cosim/step_control.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mechsim::cosim {

namespace {

constexpr double kSafety = 0.8;     // aim below the tolerance: no step is ever redone
constexpr double kMaxGrowth = 1.5;  // per step; a slow rise keeps the estimate ahead of the error
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

}  // namespace

void CouplingErrorEstimate::Channel::widen(std::span<const double> v) {
  if (lo.size() != v.size()) {
    lo.assign(v.size(), std::numeric_limits<double>::infinity());
    hi.assign(v.size(), -std::numeric_limits<double>::infinity());
  }
  for (std::size_t f = 0; f < v.size(); ++f)
    if (std::isfinite(v[f])) {
      lo[f] = std::min(lo[f], v[f]);
      hi[f] = std::max(hi[f], v[f]);
    }
}

double CouplingErrorEstimate::Channel::scale(std::size_t f) const {
  const double least = f < least_scale.size() ? least_scale[f] : 0.0;
  if (f >= lo.size() || !(hi[f] >= lo[f])) return least;
  return std::max(least, std::max(hi[f] - lo[f], std::max(std::abs(lo[f]), std::abs(hi[f]))));
}

CouplingErrorEstimate::CouplingErrorEstimate(std::vector<Edge> edges) {
  for (auto& edge : edges) {
    Channel c;
    c.order = edge.order;
    c.error_order = error_order(edge.order, edge.reconstruction);
    c.fields = std::move(edge.fields);
    c.least_scale = std::move(edge.scales);
    channels_.push_back(std::move(c));
  }
}

void CouplingErrorEstimate::used_at_step_end(std::size_t edge, std::uint64_t k, double t_k, std::span<const double> values) {
  Channel& c = channels_.at(edge);
  c.widen(values);
  if (c.order == config::EdgeOrder::jacobi) {
    c.used_step = k;
    c.used.assign(values.begin(), values.end());
    return;
  }
  if (c.history_step != UINT64_MAX && k != c.history_step + 1) c.history.clear();  // not consecutive (a restore)
  if (c.history.size() == 3) c.history.erase(c.history.begin());
  c.history.emplace_back(t_k, std::vector<double>(values.begin(), values.end()));
  c.history_step = k;
}

void CouplingErrorEstimate::received(std::size_t edge, std::uint64_t k, std::span<const double> values) {
  Channel& c = channels_.at(edge);
  if (c.order != config::EdgeOrder::jacobi) return;
  c.widen(values);
  c.received_step = k;
  c.received.assign(values.begin(), values.end());
}

std::optional<CouplingErrorEstimate::Result> CouplingErrorEstimate::ratio_at(std::uint64_t k, double tolerance) const {
  std::optional<Result> decisive;
  double smallest_factor = std::numeric_limits<double>::infinity();
  for (const Channel& c : channels_) {
    double e = 0.0;
    bool known = false;
    if (c.order == config::EdgeOrder::jacobi) {
      if (c.used_step != k || c.received_step != k || c.used.size() != c.received.size()) continue;
      for (std::size_t f : c.fields) {
        if (f >= c.used.size()) continue;
        const double s = c.scale(f);
        if (s > 0 && std::isfinite(c.used[f]) && std::isfinite(c.received[f])) e = std::max(e, std::abs(c.received[f] - c.used[f]) / s);
      }
      known = true;
    } else {
      if (c.history.size() < 3 || c.history_step != k) continue;
      const auto& [t0, v0] = c.history[0];
      const auto& [t1, v1] = c.history[1];
      const auto& [t2, v2] = c.history[2];
      const double r = (t2 - t1) / (t1 - t0);
      for (std::size_t f : c.fields) {
        const double s = c.scale(f);
        if (f >= v2.size() || !(s > 0) || !std::isfinite(v0[f]) || !std::isfinite(v1[f]) || !std::isfinite(v2[f])) continue;
        e = std::max(e, std::abs(v2[f] - (v1[f] + (v1[f] - v0[f]) * r)) / s);
      }
      known = true;
    }
    if (!known) continue;
    const double ratio = e / tolerance;
    // The factor this channel allows (before safety and limits): the smallest one decides.
    const double factor = ratio > 0 ? std::pow(ratio, -1.0 / c.error_order) : std::numeric_limits<double>::infinity();
    if (!decisive || factor < smallest_factor) {
      smallest_factor = factor;
      decisive = Result{ratio, c.error_order};
    }
  }
  return decisive;
}

StepProposal propose_step(const config::AdaptiveStepSpec& spec, double last_h,
                          const std::optional<CouplingErrorEstimate::Result>& estimate) {
  StepProposal p;
  p.error_estimate = std::numeric_limits<double>::quiet_NaN();
  double h = last_h > 0 ? last_h : spec.initial;
  if (estimate && last_h > 0) {
    p.error_estimate = estimate->ratio;
    const double factor = estimate->ratio > 0 ? kSafety * std::pow(estimate->ratio, -1.0 / estimate->order) : kMaxGrowth;
    h = last_h * std::clamp(factor, kMaxShrink, kMaxGrowth);
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
  for (const auto& [participant, p] : proposals) event = event || (p.event && p.event_time == limit);
  return end_of_step(t, h, limit, event, spec_, end_);
}

void StepAgreement::discard_before(std::uint64_t k) {
  by_step_.erase(by_step_.begin(), by_step_.lower_bound(k));
}

}  // namespace mechsim::cosim

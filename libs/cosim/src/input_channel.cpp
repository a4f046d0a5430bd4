#include "mechsim/cosim/input_channel.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace mechsim::cosim {

InputChannel::InputChannel(config::EdgeOrder order, config::Reconstruction reconstruction,
                           std::shared_ptr<const StepGrid> grid)
    : order_(order), reconstruction_(reconstruction), grid_(std::move(grid)) {
  spare_.reserve(16);  // a channel holds 3-4 samples at a time; room for bursts ahead
}

bool InputChannel::add(std::uint64_t step, const std::vector<double>& values) {
  if (auto it = samples_.find(step); it != samples_.end())
    return std::memcmp(it->second.data(), values.data(), sizeof(double) * std::min(values.size(), it->second.size())) == 0 &&
           it->second.size() == values.size();
  if (spare_.empty()) {
    samples_.emplace(step, values);
    return true;
  }
  auto node = std::move(spare_.back());
  spare_.pop_back();
  node.key() = step;
  node.mapped().assign(values.begin(), values.end());  // same width every step: no reallocation
  samples_.insert(std::move(node));
  return true;
}

const std::vector<double>* InputChannel::find(std::uint64_t step) const {
  auto it = samples_.find(step);
  return it == samples_.end() ? nullptr : &it->second;
}

bool InputChannel::ready_for_step(std::uint64_t k) const {
  // A Gauss-Seidel edge interpolates between k and k+1: both must be here. In a run's
  // order k always comes first; after a restart a partner's step-k copy may be the one
  // lost and sent again after k+1 (docs/faults.md).
  if (order_ == config::EdgeOrder::gauss_seidel) return find(k + 1) != nullptr && find(k) != nullptr;
  return find(k) != nullptr;
}

bool InputChannel::ready_for_initial() const {
  return order_ == config::EdgeOrder::jacobi || find(0) != nullptr;
}

void InputChannel::values_at(double t, std::uint64_t k, std::vector<double>& out) const {
  // The fraction of the step comes from the step index, not from accumulated time, so
  // every node reconstructs bit-identically whatever the timing.
  const double s = (t - grid_->time(k)) / grid_->step_length(k);
  const std::vector<double>* now = find(k);
  if (order_ == config::EdgeOrder::gauss_seidel) {
    const std::vector<double>* next = find(k + 1);
    if (!next || !now) throw std::logic_error("Gauss-Seidel input reconstructed without its samples");
    if (s >= 1.0) {
      out = *next;
      return;
    }
    out.resize(now->size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = (*now)[i] + s * ((*next)[i] - (*now)[i]);
    return;
  }
  extrapolate(t, s, k, out);
}

void InputChannel::extrapolate(double t, double s, std::uint64_t k, std::vector<double>& out) const {
  const std::vector<double>* now = find(k);
  if (!now) throw std::logic_error("Jacobi input reconstructed without its step-k sample");
  // On an adaptive grid the extrapolation does not reach back across an event (a sample at
  // the event's instant is its value after it): it restarts from hold, as an integrator
  // restarts at order one after a discontinuity, while the steps after the event are short.
  // A slope through a jump would extrapolate the jump (docs/accuracy.md, "Events").
  const bool restart = grid_->is_adaptive();
  const std::vector<double>* before =
      k > 0 && reconstruction_ != config::Reconstruction::hold && !(restart && grid_->is_event(k)) ? find(k - 1) : nullptr;
  const std::vector<double>* oldest =
      before && k > 1 && reconstruction_ == config::Reconstruction::quadratic && !(restart && grid_->is_event(k - 1))
          ? find(k - 2)
          : nullptr;
  if (!before) {  // hold, or the first step of an extrapolation
    out = *now;
    return;
  }
  out.resize(now->size());
  // Newton's backward form through steps k, k-1 (and k-2): exact for polynomials of the
  // reconstruction's degree; a quadratic starts as linear while k-2 does not exist yet.
  if (!grid_->uniform()) {  // the same polynomial through the samples' own instants
    const double tk = grid_->time(k), tk1 = grid_->time(k - 1);
    const double tk2 = oldest ? grid_->time(k - 2) : 0.0;
    for (std::size_t i = 0; i < out.size(); ++i) {
      const double slope = ((*now)[i] - (*before)[i]) / (tk - tk1);
      out[i] = (*now)[i] + (t - tk) * slope;
      if (oldest) {
        const double slope_before = ((*before)[i] - (*oldest)[i]) / (tk1 - tk2);
        out[i] += (t - tk) * (t - tk1) * (slope - slope_before) / (tk - tk2);
      }
    }
    return;
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double first = (*now)[i] - (*before)[i];
    out[i] = (*now)[i] + s * first;
    if (oldest) out[i] += 0.5 * s * (s + 1.0) * (first - ((*before)[i] - (*oldest)[i]));
  }
}

void InputChannel::values_at_step_end(std::uint64_t k, std::vector<double>& out) const {
  if (order_ == config::EdgeOrder::gauss_seidel) {
    const std::vector<double>* next = find(k + 1);
    if (!next) throw std::logic_error("Gauss-Seidel input reconstructed without its samples");
    out = *next;
  } else {
    extrapolate(grid_->time(k + 1), 1.0, k, out);
  }
}

void InputChannel::initial_values_at(std::vector<double>& out) const {
  if (order_ == config::EdgeOrder::gauss_seidel) {
    const std::vector<double>* first = find(0);
    if (!first) throw std::logic_error("Gauss-Seidel initial input without the step-0 sample");
    out = *first;
  } else {
    out = initial_;
  }
}

void InputChannel::discard_before(std::uint64_t k) {
  // Quadratic extrapolation at step k needs k-1 and k-2.
  std::uint64_t keep_from = k >= 2 ? k - 2 : 0;
  while (!samples_.empty() && samples_.begin()->first < keep_from) {
    if (spare_.size() < spare_.capacity()) spare_.push_back(samples_.extract(samples_.begin()));
    else samples_.erase(samples_.begin());
  }
}

}  // namespace mechsim::cosim

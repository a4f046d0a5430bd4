// The adaptive macro step (time.step: adaptive; docs/accuracy.md "Adaptive macro step"),
// without transport:
//  - CouplingErrorEstimate: one node's estimate of the coupling error of the step it just
//    took, from its own inputs: on a Jacobi edge the value it reconstructed at t_k (held or
//    extrapolated) against the partner's step-k sample that has now arrived; on a
//    Gauss-Seidel edge the step-k sample against the line through the two samples before it
//    (the curvature its linear interpolation missed); on a Jacobi edge also the change of the
//    node's watched outputs had the partner's sample been used (only that, in a block without
//    states). Each difference is divided by its scale (the largest of its range and its
//    magnitude so far, and its time.scales entry). The estimate predicts the error of a
//    later step from the measured one (e = K H^q, q the power of H it falls with: hold 1,
//    linear and Gauss-Seidel 2, quadratic 3) and K's trend.
//  - propose_step: the controller. The step after the one under way (H_k) is the longest
//    whose predicted error is 0.8 tol, at most 2 H_k and at least H_k / 5, inside [min, max].
//    No step is redone (that would need every node to roll back): the controller is kept
//    conservative instead (the 0.8, the trend, the factor 2), and a step whose estimate
//    exceeds the tolerance only makes the next one shorter.
//  - StepAgreement: every node's proposal made at step k; once all are there, t_k+2 is
//    t_k+1 plus the smallest proposed length, or the earliest discontinuity a proposal
//    announces when that comes first, or the end. One step ahead, so that the proposals
//    travel while the nodes step and nobody waits for them (the estimate acts a step later). Every node computes the same function of
//    the same doubles, so all agree bit for bit with no round trip through the launcher.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "mechsim/config/scene.h"

namespace mechsim::cosim {

// One node's proposal for step k -> k+1 (what it publishes on <node>/step).
struct StepProposal {
  double step_length = 0.0;   // s
  // An instant the step must end on when it comes before t_k + step_length (+inf: none):
  // a discontinuity the node announces (event), or an instant of a recorded run (a replay).
  double event_time = std::numeric_limits<double>::infinity();
  bool event = false;         // event_time is a discontinuity (the row logged there is after it)
  double error_estimate = 0.0;  // e / tol of the step before (NaN when none yet)
  // A state event (a root the node's integrator found: lift-off, landing) inside the step
  // that ended at t_k (NaN: none). It cannot be landed on (it was found only by taking the
  // step), so it is handled at the next step the proposals still set: that one starts again
  // from `initial`, and no node measures its coupling error across the event.
  double state_event_time = std::numeric_limits<double>::quiet_NaN();
  bool operator==(const StepProposal& o) const {
    const auto same = [](double a, double b) { return a == b || (a != a && b != b); };
    return step_length == o.step_length && event == o.event && event_time == o.event_time && same(error_estimate, o.error_estimate) &&
           same(state_event_time, o.state_event_time);
  }
};

// The agreed end of step k -> k+1.
struct AgreedStep {
  double t_next = 0.0;
  bool event = false;
  bool after_state_event = false;  // a proposal reported a state event: the step starts again from `initial`
};

class CouplingErrorEstimate {
 public:
  // An inbound edge: its kind, and the fields of its topic the node uses (the others, which
  // feed no input, are no error of this node).
  struct Edge {
    config::EdgeOrder order;
    config::Reconstruction reconstruction;
    std::vector<std::size_t> fields;
    std::vector<double> scales = {};  // per topic field: the least scale (time.scales), 0: none
    // Jacobi: the node's outputs the edge's inputs reach directly (feedthrough) and whose
    // error matters beyond the node (PlannedNode::watched_outputs), with their least scales:
    // the edge's error is also measured as its effect on them.
    std::vector<std::size_t> outputs = {};
    std::vector<double> output_scales = {};
  };
  explicit CouplingErrorEstimate(std::vector<Edge> edges);
  // After step k-1 -> k: what channel `edge` reconstructed at t_k (on a Gauss-Seidel edge
  // that is the step-k sample itself). `event`: t_k is a discontinuity, so no step whose
  // reconstruction reaches back across it measures the smooth signal after it.
  void used_at_step_end(std::size_t edge, std::uint64_t k, double t_k, std::span<const double> values, bool event = false);
  // The partner's step-k sample of a Jacobi edge, once it is there; with the node's outputs
  // at t_k and, per Edge::outputs entry, how much they change when the sample replaces what
  // the node used (empty: no outputs measured).
  void received(std::size_t edge, std::uint64_t k, std::span<const double> values,
                std::span<const double> outputs = {}, std::span<const double> output_change = {});
  struct Result {
    double ratio;    // e / tol of the step that ended at t_k, the worst channel's
    int order;       // q of the channel that decides the next step
    // The longest step after the one under way whose predicted error stays within the
    // controller's safety times the tolerance (+inf: no channel limits it).
    double longest;
  };
  // Edge::outputs of `edge`: the outputs whose change received() expects, in that order.
  const std::vector<std::size_t>& outputs(std::size_t edge) const { return channels_.at(edge).outputs; }
  // A discontinuity inside the step that ended at t_k (a state event): no step whose
  // reconstruction reaches back before t_k is measured.
  void discontinuity_at(std::uint64_t k);
  // nullopt when no channel can tell yet (the first steps, and the steps just after an event).
  // The prediction: per field, the measured error of the step k-1 -> k (length a) as
  // e = K a^q (a^q: the reach), K's trend from the two steps before (dK/dt between midpoints), K carried to
  // the start of the step after the one under way (length `current_h`), and the error of a
  // step h there bounded by (|K| + |dK/dt| h / 2) times its reach (h^q on equal steps; a
  // Jacobi edge's h (h + current_h) ... on unequal ones, Measured::reach). The trend matters where a signal's
  // slope passes through zero: the measured error is small there, the next steps' is not.
  std::optional<Result> at(std::uint64_t k, double tolerance, double current_h) const;

 private:
  struct Measured {
    std::uint64_t step;      // the step k-1 -> k that ended at t_k
    double length;           // t_k - t_k-1
    // Signed e / scale / reach (0: not measured), per topic field, then per output.
    std::vector<double> k;
    // The reconstruction's reach at t_k: length^q on equal steps; on unequal ones the product
    // of the distances from t_k to the samples it used (length (length + t_k-1 - t_k-2) ...).
    double reach = 0.0;
  };
  struct Channel {
    config::EdgeOrder order;
    int error_order;
    int reaches_back;        // how many samples before t_k the reconstruction at t_k uses
    std::vector<std::size_t> fields;
    std::uint64_t used_step = UINT64_MAX;
    std::vector<double> used;                 // reconstructed at t_used_step
    // The instants of the last steps (oldest first) and the last event step.
    std::vector<std::pair<std::uint64_t, double>> instants;
    std::uint64_t last_event = 0;
    // Gauss-Seidel: the samples of the last three steps (oldest first).
    std::vector<std::vector<double>> history;
    std::optional<Measured> last, before, older;  // the last three steps measured
    std::size_t topic_size = 0;               // fields of the topic (the first entries of K), fixed at construction
    std::vector<std::size_t> outputs;         // Edge::outputs
    std::vector<double> lo, hi;               // per topic field then per output, over every value seen
    std::vector<double> least_scale;          // likewise (time.scales), 0: none
    void widen(std::span<const double> v, std::size_t offset = 0);
    double scale(std::size_t entry) const;
    double instant(std::uint64_t k) const;    // NaN when not kept
    // `difference`: per topic field, then per output (or only the fields).
    void measured(std::uint64_t k, std::span<const double> difference);
  };
  std::vector<Channel> channels_;
};

// The controller's proposal made at step k, for the step after the one under way (of length
// `current_h`; 0 after a restart: the spec's initial step): the estimate's longest step,
// within [current_h / 5, 2 current_h] and [min, max] (nullopt: keep the step). The
// scheduled discontinuities of the grid are landed on by the caller.
StepProposal propose_step(const config::AdaptiveStepSpec& spec, double current_h,
                          const std::optional<CouplingErrorEstimate::Result>& estimate);

// The end of a step from t_k: t_k + h, or `limit` when it comes first or less than `min`
// after (then an event when `limit_is_event`), or the end when less than `min` remains.
AgreedStep end_of_step(double t_k, double h, double limit, bool limit_is_event, const config::AdaptiveStepSpec& spec,
                       double end);

// The participants' proposals, by step. The proposals made at step k set t_k+2 (they travel
// while the nodes take step k -> k+1); t_1 is t_0 + `initial` (StepGrid::adaptive).
class StepAgreement {
 public:
  StepAgreement(std::size_t participants, const config::AdaptiveStepSpec& spec, double end)
      : participants_(participants), spec_(spec), end_(end) {}
  // False when the participant already proposed something else for step k (a foreign writer
  // or a bug: the caller refuses it). The caller leaves out proposals of steps it has passed.
  bool add(std::size_t participant, std::uint64_t k, const StepProposal& p);
  bool complete(std::uint64_t k) const;
  // The participants whose proposal of step k is not here yet.
  std::vector<std::size_t> missing(std::uint64_t k) const;
  // Requires complete(k): the end of the step that starts at `t` (t_k+1).
  AgreedStep agreed(std::uint64_t k, double t) const;
  // Forgets the proposals of steps before k.
  void discard_before(std::uint64_t k);

 private:
  std::size_t participants_;
  config::AdaptiveStepSpec spec_;
  double end_;
  std::map<std::uint64_t, std::map<std::size_t, StepProposal>> by_step_;
};

}  // namespace mechsim::cosim

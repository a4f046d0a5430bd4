#include "sample_gate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mechsim/cosim/step_topic.h"
#include "node_failure.h"

namespace mechsim::cosim {

SampleGate::SampleGate(const ScenePlan& plan, const PlannedNode& node, NodeEndpoints& io, NodeStepper& stepper,
                       const RollbackSession& rollback, std::uint64_t run_id, int domain, bool resumed, SteadyNow now)
    : plan_(plan),
      node_(node),
      io_(io),
      stepper_(stepper),
      rollback_(rollback),
      run_id_(run_id),
      domain_(domain),
      now_(now),
      next_step_(io.inputs(), 0),
      next_step_known_(io.inputs(), !resumed),
      checked_fields_(node.inputs.size()) {
  // Fields the publisher does not compute are NaN by design (PlannedNode::published_outputs).
  for (std::size_t e = 0; e < node.inputs.size(); ++e) {
    const PlannedNode& publisher = plan.node(node.inputs[e].from);
    for (const auto& [field, input] : node.inputs[e].field_to_input)
      if (field < static_cast<int>(publisher.published_outputs.size()) && publisher.published_outputs[static_cast<std::size_t>(field)] >= 0)
        checked_fields_[e].push_back(field);
  }
}

// A stream goes on one step after the other. After a rollback, for a while, a step from the
// rollback's step up to the newest one seen is a repeat (checked for equal values where
// still in use by the input channel).
bool SampleGate::in_sequence(std::size_t e, std::uint64_t step) const {
  if (!next_step_known_[e] || step == next_step_[e]) return true;
  const auto& k = rollback_.rollback_step();
  return k && step >= *k && step < next_step_[e] && rollback_.within_after_resume(RollbackSession::kLingeringAfterResume);
}

// The message names the writers the reader is matched with: the intruder among them.
void SampleGate::foreign(const transport::SampleReader* r, const std::string& topic, const std::string& from,
                         const std::string& what) const {
  std::string ids;
  for (const auto& id : r->matched_writer_ids()) ids += (ids.empty() ? "" : "; ") + id;
  throw NodeFailure(transport::NodeError::foreign_data,
                    "foreign data on topic '" + topic + "' (the scene's only writer is participant '" + from + "'): " + what +
                        "; " + std::to_string(r->matched_writers()) + " writer(s) matched" + (ids.empty() ? "" : " (" + ids + ")") +
                        "; a participant that does not belong to this run writes into its domain " +
                        std::to_string(domain_) + " (docs/faults.md)");
}

// No hold (and no failure) for a second writer while a restarted partner's dead one may
// still linger; after that a second writer is one like any other.
bool SampleGate::holding() const {
  return second_writer_since_.has_value() && !rollback_.within_after_resume(RollbackSession::kLingeringAfterResume);
}

bool SampleGate::hold_for_second_writer() {
  const auto& watched = io_.watched();
  const auto w = std::find_if(watched.begin(), watched.end(), [](const WatchedReader& r) { return r.reader->matched_writers() > 1; });
  if (w == watched.end()) {
    second_writer_since_.reset();
    return false;
  }
  if (!second_writer_since_) second_writer_since_ = now_();
  if (std::chrono::duration<double>(now_() - *second_writer_since_).count() > RollbackSession::kForeignWriterGrace &&
      !rollback_.within_after_resume(RollbackSession::kLingeringAfterResume))
    foreign(w->reader, w->topic, w->from,
            "more than one writer for " + std::to_string(static_cast<int>(RollbackSession::kForeignWriterGrace)) + " s");
  return holding();
}

void SampleGate::check_plausible(std::size_t e, const transport::SampleHeader& h, const std::vector<double>& v) {
  const InboundEdge& edge = node_.inputs[e];
  for (const int field : checked_fields_[e]) {
    const transport::FieldInfo& f = edge.type->fields[static_cast<std::size_t>(field)];
    const double x = v[static_cast<std::size_t>(field)];
    if (std::isfinite(x) && x >= f.min && x <= f.max) continue;
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s = %.6g%s%s outside [%g, %g]", f.name.c_str(), x, f.unit.empty() ? "" : " ", f.unit.c_str(), f.min, f.max);
    // With a second writer matched the sample is most likely not the partner's at all.
    if (io_.input(e).matched_writers() > 1)
      foreign(&io_.input(e), edge.topic, edge.from, std::string("an implausible sample for step ") + std::to_string(h.step) + " (" + buf + ")");
    // From the partner itself: it diverged (its own guard had not caught it yet) or its
    // data is corrupted; the launcher then looks for a stable macro step.
    throw NodeFailure(transport::NodeError::implausible_input,
                      "implausible sample on topic '" + edge.topic + "' from participant '" + edge.from + "', step " +
                          std::to_string(h.step) + ": " + buf + " (bounds: docs/dds.md, 'Plausible samples'): participant '" +
                          edge.from + "' diverged, or its data is corrupted");
  }
}

// Input edge e's reliable stream, then its redundant twin; true when anything was taken.
bool SampleGate::drain_input(std::size_t e) {
  bool took = false;
  const InboundEdge& edge = node_.inputs[e];
  transport::SampleReader& reader = io_.input(e);
  transport::SampleHeader h;
  while (reader.take(h, received_)) {
    took = true;
    if (h.run_id != run_id_) continue;
    if (!in_sequence(e, h.step)) {
      const bool one_writer = reader.matched_writers() == 1;
      // A step taken before, again, from the one writer the plan expects: a partner that
      // stalled writes its newest samples once more (StallResend). Dropped; where the step
      // is still held its values must be the same.
      if (h.step < next_step_[e] && one_writer) {
        if (h.step + 2 >= stepper_.step() && !stepper_.channel(e).add(h.step, received_))
          foreign(&reader, edge.topic, edge.from, "two different samples for step " + std::to_string(h.step));
        continue;
      }
      // A step ahead of the one due, from the one writer the plan expects: the DDS layer
      // skipped a sample of its reliable stream (seen under 5 % loss between Fast DDS and
      // Cyclone at the start of a run); the step due comes from the redundant copy or the
      // run stalls and ends at the partition grace. Anything else out of order is foreign.
      if (!(h.step > next_step_[e] && one_writer))
        foreign(&reader, edge.topic, edge.from, "step " + std::to_string(h.step) + " arrived where step " + std::to_string(next_step_[e]) + " was due");
      std::printf("warning: topic '%s': step %llu arrived where step %llu was due (one writer matched): the reliable stream skipped; taking it\n",
                  edge.topic.c_str(), static_cast<unsigned long long>(h.step), static_cast<unsigned long long>(next_step_[e]));
    }
    next_step_[e] = next_step_known_[e] ? std::max(next_step_[e], h.step + 1) : h.step + 1;
    next_step_known_[e] = true;
    check_plausible(e, h, received_);
    if (h.step + 2 >= stepper_.step() && !stepper_.channel(e).add(h.step, received_))
      foreign(&reader, edge.topic, edge.from, "two different samples for step " + std::to_string(h.step));
  }
  // The twin copy: a step already there (or consumed) is dropped as a duplicate.
  transport::SampleReader* twin = io_.twin_input(e);
  while (twin && twin->take(h, received_)) {
    took = true;
    if (h.run_id != run_id_ || h.step < stepper_.step()) continue;
    check_plausible(e, h, received_);
    if (!stepper_.channel(e).add(h.step, received_))
      foreign(twin, transport::redundant_topic(edge.topic), edge.from, "two different samples for step " + std::to_string(h.step));
  }
  return took;
}

void SampleGate::drain() {
  bool took = false;
  for (std::size_t e = 0; e < io_.inputs(); ++e) took = drain_input(e) || took;
  transport::SampleHeader h;
  for (transport::SampleReader* cut : {io_.cut_input(), io_.twin_cut_input()})
    while (cut && cut->take(h, received_)) {
      took = true;
      if (h.run_id == run_id_) stepper_.add_partner_prediction(h.step, received_);
    }
  for (const auto& r : io_.proposal_inputs())
    while (r.reader->take(h, received_)) {
      took = true;
      if (h.run_id != run_id_) continue;
      const StepProposal p = proposal_from_fields(received_);
      if (!(p.step_length > 0) || !std::isfinite(p.step_length))
        foreign(r.reader.get(), r.topic, plan_.nodes()[r.participant].name(),
                "a step proposal of length " + std::to_string(p.step_length) + " s for step " + std::to_string(h.step));
      stepper_.add_proposal(r.participant, h.step, p);
    }
  if (took) hold_for_second_writer();
}

}  // namespace mechsim::cosim

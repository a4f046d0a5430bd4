#include "partition_watch.h"

#include <cstdio>

#include "mechsim/cosim/step_topic.h"
#include "node_failure.h"

namespace mechsim::cosim {

namespace {

// "participant 'slide' (topic slide/state) on host c (10.77.0.3)" for failure messages.
std::string describe_partner(const config::Scene& scene, const std::string& participant, const std::string& topic) {
  std::string out = "participant '" + participant + "' (topic " + topic + ")";
  const config::ParticipantSpec* p = scene.find_participant(participant);
  if (p && !p->host.empty())
    if (const config::HostSpec* h = scene.find_host(p->host)) out += " on host " + h->name + " (" + h->address + ")";
  return out;
}

}  // namespace

PartitionWatch::PartitionWatch(const ScenePlan& plan, const PlannedNode& node, double partition_grace, SteadyNow now)
    : plan_(plan), node_(node), grace_(partition_grace), now_(now), waiting_since_(now()) {}

void PartitionWatch::check(NodeStepper& stepper, bool initialised, bool lenient) {
  if (stepper.step() != waiting_step_ || !initialised || lenient) {
    waiting_step_ = initialised ? stepper.step() : UINT64_MAX;
    waiting_since_ = now_();
    return;
  }
  const double waited = std::chrono::duration<double>(now_() - waiting_since_).count();
  if (waited <= grace_) return;
  const config::Scene& scene = plan_.scene();
  std::string missing;
  for (std::size_t e = 0; e < node_.inputs.size(); ++e)
    if (!stepper.channel(e).ready_for_step(stepper.step()))
      missing += (missing.empty() ? "" : ", ") + describe_partner(scene, node_.inputs[e].from, node_.inputs[e].topic);
  if (node_.cut && missing.empty()) missing = describe_partner(scene, node_.cut->partner, node_.cut->partner_topic);
  if (missing.empty())  // an adaptive step waits for the partners' proposals
    for (const std::size_t i : stepper.missing_proposals())
      missing += (missing.empty() ? "" : ", ") + describe_partner(scene, plan_.nodes()[i].name(), step_topic(plan_.nodes()[i].name()));
  char buf[96];
  std::snprintf(buf, sizeof buf, "no sample for step %llu for %.1f s (faults.partition_grace %g s) from ",
                static_cast<unsigned long long>(stepper.step()), waited, grace_);
  throw NodeFailure(transport::NodeError::partner_unreachable, std::string("unreachable: ") + buf + missing);
}

}  // namespace mechsim::cosim

// <node>/step (idl/step.idl): a node's proposal for the next macro step of a run with an
// adaptive step, as the flat field list the transport carries (docs/accuracy.md,
// "Adaptive macro step").
#pragma once

#include <string>
#include <vector>

#include "mechsim/cosim/step_control.h"
#include "mechsim/transport/topic_types.h"

namespace mechsim::cosim {

inline std::string step_topic(const std::string& participant) { return participant + "/step"; }
const transport::TopicType& step_proposal_type();
// Fields in the order of idl/step.idl: step_length, event, event_time, error_estimate.
void proposal_to_fields(const StepProposal& p, std::vector<double>& fields);
StepProposal proposal_from_fields(const std::vector<double>& fields);

}  // namespace mechsim::cosim

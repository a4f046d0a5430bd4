#include "mechsim/cosim/step_topic.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace mechsim::cosim {

const transport::TopicType& step_proposal_type() {
  static const transport::TopicType* type = [] {
    const transport::TopicType* t = transport::find_topic_type("StepProposal");
    if (!t) throw std::logic_error("topic type StepProposal (idl/step.idl) is not registered");
    return t;
  }();
  return *type;
}

void proposal_to_fields(const StepProposal& p, std::vector<double>& fields) {
  fields.assign({p.step_length, p.event ? 1.0 : 0.0, std::isfinite(p.event_time) ? p.event_time : std::nan(""), p.error_estimate,
                 p.state_event_time});
}

StepProposal proposal_from_fields(const std::vector<double>& fields) {
  if (fields.size() < 5) throw std::invalid_argument("step proposal: expected 5 fields");
  StepProposal p;
  p.step_length = fields[0];
  p.event = fields[1] != 0.0;
  p.event_time = std::isfinite(fields[2]) ? fields[2] : std::numeric_limits<double>::infinity();
  p.error_estimate = fields[3];
  p.state_event_time = fields[4];
  return p;
}

}  // namespace mechsim::cosim

#include "control_inbox.h"

#include "node_failure.h"

namespace mechsim::cosim {

ControlInbox::ControlInbox(transport::Participant& participant, std::uint64_t run_id, std::string control_writer, int domain)
    : reader_(participant.create_control_reader()), run_id_(run_id), control_writer_(std::move(control_writer)), domain_(domain) {}

// mechsim/control has one writer, the launcher, whose GUID the node got on its command
// line. A command of another run (a reused domain's stale sample) is ignored; a command
// of this run from any other writer is an intruder's: start, stop or abort alike.
bool ControlInbox::for_this_run(const transport::ControlMessage& c) const {
  if (c.run_id != run_id_) return false;
  if (!control_writer_.empty() && c.writer != control_writer_) {
    std::string ids;
    for (const auto& id : reader_->matched_writer_ids()) ids += (ids.empty() ? "" : "; ") + id;
    throw NodeFailure(transport::NodeError::foreign_data,
                      "foreign data on topic 'mechsim/control' (the scene's only writer is the launcher, GUID " +
                          control_writer_ + "): command " + std::to_string(static_cast<int>(c.command)) +
                          " for this run from writer " + (c.writer.empty() ? std::string("(unknown)") : c.writer) +
                          (ids.empty() ? "" : "; matched writers: " + ids) +
                          "; a participant that does not belong to this run writes into its domain " +
                          std::to_string(domain_) + " (docs/faults.md)");
  }
  return true;
}

std::optional<transport::ControlMessage> ControlInbox::next() {
  while (auto c = reader_->take())
    if (for_this_run(*c)) return c;
  return std::nullopt;
}

}  // namespace mechsim::cosim

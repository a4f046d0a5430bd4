// The launcher's commands to this node (mechsim/control): only those of this run, and only
// from the launcher's control writer.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "mechsim/transport/participant.h"

namespace mechsim::cosim {

class ControlInbox {
 public:
  // control_writer: the launcher's writer GUID (transport::guid_text); "" = not checked.
  ControlInbox(transport::Participant& participant, std::uint64_t run_id, std::string control_writer, int domain);
  // The next command of this run; nullopt when none is waiting. Throws NodeFailure
  // (foreign data) for a command of this run from another writer.
  std::optional<transport::ControlMessage> next();
  static bool ends_the_run(const transport::ControlMessage& c) {
    return c.command == transport::ControlCommand::abort || c.command == transport::ControlCommand::stop;
  }

 private:
  bool for_this_run(const transport::ControlMessage& c) const;

  std::unique_ptr<transport::ControlReader> reader_;
  std::uint64_t run_id_;
  std::string control_writer_;
  int domain_;
};

}  // namespace mechsim::cosim

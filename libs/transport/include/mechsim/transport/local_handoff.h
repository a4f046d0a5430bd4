// In-memory hand-off between the participants of one process that one thread steps (a
// process group's executor, docs/node-loop.md "One executor per process"). Each member keeps
// its own participant for everything else; a topic that a member of the same executor
// writes is read from memory instead of from DDS: no serialization, no DDS wake-up, no
// thread hand-off. The writer still publishes it on DDS while anyone outside reads it
// (tools, recordings, readers in other processes or on other hosts), so the outside sees
// what it sees without the hand-off, and the values are the ones a DDS round trip gives
// (as_on_the_wire).
//
// Not thread-safe, on purpose: every member's data endpoints are created and used on the
// executor's one thread. Control and status pass through to the member's own participant.
#pragma once

#include <memory>
#include <set>
#include <string>

#include "mechsim/transport/participant.h"

namespace mechsim::transport {

class LocalHandoff {
 public:
  // local_topics: every data topic a member of this executor writes (its state, its cut
  // prediction, its step proposals).
  explicit LocalHandoff(std::set<std::string> local_topics);
  ~LocalHandoff();
  LocalHandoff(const LocalHandoff&) = delete;
  LocalHandoff& operator=(const LocalHandoff&) = delete;

  // A member's view of the transport: `own` for everything but the local topics' readers.
  // The hand-off must outlive what it returns.
  std::unique_ptr<Participant> member(std::unique_ptr<Participant> own);
  bool is_local(const std::string& topic) const { return topics_.count(topic) > 0; }

  struct Bus;

 private:
  std::set<std::string> topics_;
  std::unique_ptr<Bus> bus_;
};

}  // namespace mechsim::transport

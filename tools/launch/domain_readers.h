// The readers on a run's domain that the nodes' writers must have matched before the start.
//
// A recorder the user started before the launch (`mechsim record`, `topic echo`) reads a
// node's topic from step 0 only if the node's writer has matched its reader before the
// node writes; DDS discovery completes on each side on its own, so the recorder seeing the
// writer says nothing about the writer seeing the reader (a sample written in between
// never reaches it: VOLATILE). The launcher counts the readers of each topic through
// discovery and starts the run once every node reports at least that many matched
// readers (Status.readers_matched). docs/recording.md, 'From the first step'.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <utility>

#include "mechsim/transport/raw.h"

namespace mechsim::launch {

class DomainReaders {
 public:
  // A Cyclone discovery participant of its own on `domain` (the DDS environment and
  // identity of the launcher). Never throws: without one (`available()` false) nothing is
  // counted and nothing waited for.
  explicit DomainReaders(int domain);
  bool available() const { return participant_ != nullptr; }
  // Readers of other participants on the domain as discovered so far, by topic and type
  // (a reader of another type never matches): one discovery snapshot per call.
  std::map<std::pair<std::string, std::string>, int> by_topic_and_type();
  const std::string& problem() const { return problem_; }

 private:
  std::unique_ptr<transport::RawParticipant> participant_;
  std::string problem_;
};

}  // namespace mechsim::launch

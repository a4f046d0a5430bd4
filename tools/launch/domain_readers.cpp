#include "domain_readers.h"

#include <exception>

namespace mechsim::launch {

DomainReaders::DomainReaders(int domain) {
  try {
    participant_ = transport::create_raw_participant("cyclone", domain);
  } catch (const std::exception& e) {
    problem_ = e.what();
  }
}

std::map<std::pair<std::string, std::string>, int> DomainReaders::by_topic_and_type() {
  std::map<std::pair<std::string, std::string>, int> readers;
  if (!participant_) return readers;
  for (const auto& t : participant_->discovered_topics()) readers[{t.name, t.type_name}] += t.subscribers;
  return readers;
}

}  // namespace mechsim::launch

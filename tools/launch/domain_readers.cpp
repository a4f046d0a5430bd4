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

int DomainReaders::on_topic(const std::string& topic, const std::string& type_name) {
  if (!participant_) return 0;
  int readers = 0;
  for (const auto& t : participant_->discovered_topics())
    if (t.name == topic && t.type_name == type_name) readers += t.subscribers;
  return readers;
}

}  // namespace mechsim::launch

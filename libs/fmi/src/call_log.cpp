#include "call_log.h"

#include <cstdio>

namespace mechsim::fmi {

namespace {
constexpr std::size_t kKeptMessages = 8;
}

void CallLog::add_message(const std::string& status, const std::string& category, const std::string& message) {
  messages_.push_back("[" + status + (category.empty() ? "" : " " + category) + "] " + message);
  if (messages_.size() > kKeptMessages) messages_.pop_front();
}

void CallLog::fail(const std::string& function, const std::string& status) const {
  char when[64];
  std::snprintf(when, sizeof when, "%.9g", time_);
  std::string what = function + " returned " + status + " at t = " + when + " s";
  if (!messages_.empty()) {
    what += "; the FMU logged:";
    for (const auto& m : messages_) what += "\n  " + m;
  }
  throw FmuError(label_, what);
}

void CallLog::fail_at_setup(const std::string& what) const {
  std::string text = what;
  if (!messages_.empty()) {
    text += "; the FMU logged:";
    for (const auto& m : messages_) text += "\n  " + m;
  }
  throw FmuError(label_, text);
}

}  // namespace mechsim::fmi

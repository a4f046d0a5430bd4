// What an instance remembers for its error messages: the FMU's own log messages (the last
// few) and the time of the call, so that a failed call says which function, when, and what
// the FMU said about it.
#pragma once

#include <deque>
#include <string>

#include "mechsim/fmi/error.h"

namespace mechsim::fmi {

class CallLog {
 public:
  explicit CallLog(FmuLabel label) : label_(std::move(label)) {}
  const FmuLabel& label() const { return label_; }
  void set_time(double t) { time_ = t; }
  void add_message(const std::string& status, const std::string& category, const std::string& message);
  // Throws FmuError: "<function> returned <status> at t = <time> s; the FMU logged: ...".
  [[noreturn]] void fail(const std::string& function, const std::string& status) const;
  [[noreturn]] void fail_at_setup(const std::string& what) const;

 private:
  FmuLabel label_;
  double time_ = 0.0;
  std::deque<std::string> messages_;
};

}  // namespace mechsim::fmi

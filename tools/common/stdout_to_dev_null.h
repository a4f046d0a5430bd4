// The in-process nodes print their own lines ("done: ...") on stdout; a command whose
// stdout is a table (`mechsim bench`, `mechsim sweep`) keeps them out while one of these lives.
#pragma once

namespace mechsim::tools {

class StdoutToDevNull {
 public:
  StdoutToDevNull();
  ~StdoutToDevNull();
  StdoutToDevNull(const StdoutToDevNull&) = delete;
  StdoutToDevNull& operator=(const StdoutToDevNull&) = delete;

 private:
  int saved_ = -1;
};

}  // namespace mechsim::tools

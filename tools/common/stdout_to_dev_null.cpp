#include "stdout_to_dev_null.h"

#include <unistd.h>

#include <cstdio>

namespace mechsim::tools {

StdoutToDevNull::StdoutToDevNull() {
  std::fflush(stdout);
  saved_ = dup(1);
  if (FILE* null = std::fopen("/dev/null", "w")) {
    dup2(fileno(null), 1);
    std::fclose(null);
  }
}

StdoutToDevNull::~StdoutToDevNull() {
  std::fflush(stdout);
  if (saved_ >= 0) {
    dup2(saved_, 1);
    close(saved_);
  }
}

}  // namespace mechsim::tools

#include "ode_backend.h"

#include <stdexcept>

namespace mechsim::solve::detail {

void OdeBackend::keep_error_message(int error_code, const char* module, const char* function,
                                    char* msg, void* backend) {
  if (error_code >= 0) return;  // warnings (e.g. "t + h = t") are not failures
  auto* self = static_cast<OdeBackend*>(backend);
  self->last_message_ = std::string(module) + "::" + function + ": " + msg;
}

void OdeBackend::require(int flag, const char* call, const BlockProblem& problem) const {
  if (flag >= 0) return;
  throw std::runtime_error("mechsim::solve: " + std::string(call) + " failed for block '" +
                           problem.block.type_name() + "' with flag " + std::to_string(flag) +
                           (last_message_.empty() ? "" : " (" + last_message_ + ")"));
}

}  // namespace mechsim::solve::detail

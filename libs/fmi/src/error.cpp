#include "mechsim/fmi/error.h"

namespace mechsim::fmi {

std::string FmuLabel::describe() const {
  std::string s = "FMU '" + file + "'";
  if (!participant.empty()) s += " (participant '" + participant + "')";
  return s;
}

}  // namespace mechsim::fmi

// What went wrong with an FMU, said with where: every message starts with the FMU file and,
// where known, the participant that uses it ("FMU 'fmus/ctrl.fmu' (participant 'ctrl'): ...").
#pragma once

#include <stdexcept>
#include <string>

namespace mechsim::fmi {

// Which FMU a message is about: its file as the user named it and the participant using it
// (empty outside a scene, e.g. `mechsim fmu info`).
struct FmuLabel {
  std::string file;
  std::string participant;
  std::string describe() const;  // "FMU 'FILE'" or "FMU 'FILE' (participant 'NAME')"
};

class FmuError : public std::runtime_error {
 public:
  FmuError(const FmuLabel& label, const std::string& what)
      : std::runtime_error(label.describe() + ": " + what) {}
};

}  // namespace mechsim::fmi

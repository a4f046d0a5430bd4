// What the FMI 2 and FMI 3 entry layers share: an instance's exported participant, built
// from resources/participant.yaml of the folder the importer names (an FMI 2 URI or an
// FMI 3 path). Each layer guards its calls so that an exception becomes a logged error
// status (nothing may unwind into the importer).
#pragma once

#include <exception>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "mechsim/fmi_export/exported_participant.h"

namespace mechsim::fmi_export {

// The resources folder of an FMI 2 URI ("file:///p", "file:/p", percent-encoded) or of an
// FMI 3 path ("/p/"), without a trailing slash.
inline std::string resources_folder(std::string location) {
  if (location.rfind("file://", 0) == 0) location.erase(0, 7);
  else if (location.rfind("file:", 0) == 0) location.erase(0, 5);
  std::string decoded;
  for (std::size_t i = 0; i < location.size(); ++i) {
    if (location[i] == '%' && i + 2 < location.size()) {
      decoded += static_cast<char>(std::stoi(location.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      decoded += location[i];
    }
  }
  while (decoded.size() > 1 && decoded.back() == '/') decoded.pop_back();
  return decoded;
}

inline std::unique_ptr<ExportedParticipant> load_participant(const std::string& resource_location) {
  const std::string file = resources_folder(resource_location) + "/participant.yaml";
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file + " (the FMU's resources/participant.yaml)");
  std::stringstream text;
  text << in.rdbuf();
  return std::make_unique<ExportedParticipant>(read_export_config(text.str(), file));
}

}  // namespace mechsim::fmi_export

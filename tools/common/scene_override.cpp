#include "scene_override.h"

namespace mechsim::tools {

std::string scene_override(const std::string& set) {
  const std::string key = set.substr(0, set.find('='));
  const std::string head = key.substr(0, key.find('.'));
  // Keys that start with a top-level scene section are taken as they are; anything else
  // is <participant>.<param>.
  static const char* const sections[] = {"participants", "time", "dds", "hosts", "faults", "realtime", "record", "design", "report", "compare"};
  bool scene_key = key.find('.') == std::string::npos || head.rfind("connections", 0) == 0;
  for (const char* section : sections) scene_key = scene_key || head == section;
  return scene_key ? set : "participants." + head + ".params" + set.substr(head.size());
}

}  // namespace mechsim::tools

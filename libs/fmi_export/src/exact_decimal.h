// How the exporter writes a double into participant.yaml and modelDescription.xml: the
// shortest decimal that reads back as the same double (the FMU must rebuild the same block).
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

namespace mechsim::fmi_export {

inline std::string exact(double v) {
  char buf[32];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

}  // namespace mechsim::fmi_export

// Where the launcher finds what it starts: node executables next to the running `mechsim`
// (build/bin), and the DDS configuration under the project's config/dds (MECHSIM_HOME
// overrides the project folder compiled in).
#pragma once

#include <string>

namespace mechsim::launch {

std::string executable_dir();
std::string node_executable(const std::string& node_type);
std::string project_dir();
// Points CYCLONEDDS_URI at config/dds/cyclonedds-loopback.xml unless the user set it.
// Children inherit it.
void configure_dds_environment();

}  // namespace mechsim::launch

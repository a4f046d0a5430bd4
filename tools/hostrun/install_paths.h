// Where the launcher finds what it starts: node executables next to the running `mechsim`
// (build/bin), and the DDS configuration under the project's config/dds (MECHSIM_HOME
// overrides the project folder compiled in).
#pragma once

#include <string>

namespace mechsim::hostrun {

std::string executable_dir();
std::string node_executable(const std::string& node_type);
std::string project_dir();
// Points CYCLONEDDS_URI at config/dds/cyclonedds-loopback.xml and
// FASTRTPS_DEFAULT_PROFILES_FILE at config/dds/fastdds-{shm,udp}.xml (MECHSIM_FASTDDS_TRANSPORT)
// unless the user set them. Children inherit both.
void configure_dds_environment();

}  // namespace mechsim::hostrun

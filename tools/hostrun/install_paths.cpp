#include "install_paths.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace mechsim::hostrun {

namespace fs = std::filesystem;

std::string executable_dir() {
  std::error_code ec;
  fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot locate the running executable: " + ec.message());
  return self.parent_path().string();
}

std::string node_executable(const std::string& node_type) {
  fs::path exe = fs::path(executable_dir()) / node_type;
  if (::access(exe.c_str(), X_OK) != 0)
    throw std::runtime_error("node executable " + exe.string() + " is missing: build it (cmake --build build)");
  return exe.string();
}

std::string project_dir() {
  if (const char* home = std::getenv("MECHSIM_HOME")) return home;
  return MECHSIM_SOURCE_DIR;
}

void configure_dds_environment() {
  auto config_file = [](const std::string& name) {
    fs::path xml = fs::path(project_dir()) / "config/dds" / name;
    if (!fs::exists(xml)) throw std::runtime_error(xml.string() + " is missing (set MECHSIM_HOME to the project folder)");
    return xml.string();
  };
  // The user's own configuration wins, vendor by vendor.
  if (!std::getenv("CYCLONEDDS_URI"))
    ::setenv("CYCLONEDDS_URI", ("file://" + config_file("cyclonedds-loopback.xml")).c_str(), 1);
  if (!std::getenv("FASTRTPS_DEFAULT_PROFILES_FILE")) {
    // Fast DDS 2.9 reads its transports only from an XML profile: shared memory (default)
    // or UDP loopback only, chosen by MECHSIM_FASTDDS_TRANSPORT.
    const char* env = std::getenv("MECHSIM_FASTDDS_TRANSPORT");
    const std::string transport = env && *env ? env : "shm";
    if (transport != "shm" && transport != "udp")
      throw std::runtime_error("MECHSIM_FASTDDS_TRANSPORT: expected 'shm' or 'udp', got '" + transport + "'");
    ::setenv("FASTRTPS_DEFAULT_PROFILES_FILE", config_file("fastdds-" + transport + ".xml").c_str(), 1);
  }
}

}  // namespace mechsim::hostrun

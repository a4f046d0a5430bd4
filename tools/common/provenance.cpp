#include "provenance.h"

#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "mechsim/config/hash.h"

// Set by tools/common/CMakeLists.txt.
#ifndef MECHSIM_VERSION
#error "MECHSIM_VERSION must be defined by the build"
#endif
#ifndef MECHSIM_GIT_COMMIT
#error "MECHSIM_GIT_COMMIT must be defined by the build"
#endif

namespace mechsim::tools {
namespace {

std::string utc_now_iso8601() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buf;
}

std::string host_name() {
  char buf[HOST_NAME_MAX + 1] = {};
  if (gethostname(buf, sizeof buf - 1) != 0) return "unknown";
  return buf;
}

std::string file_sha256(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw std::runtime_error("cannot read scene file " + path +
                             " to hash it: " + std::strerror(errno));
  }
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return config::sha256_hex(bytes.str());
}

}  // namespace

nlohmann::json provenance(const std::string& scene_path_or_empty) {
  nlohmann::json p;
  p["mechsim_version"] = MECHSIM_VERSION;
  p["git_commit"] = MECHSIM_GIT_COMMIT;
  if (scene_path_or_empty.empty()) {
    p["scene_file"] = nullptr;
    p["scene_sha256"] = nullptr;
  } else {
    p["scene_file"] = scene_path_or_empty;
    p["scene_sha256"] = file_sha256(scene_path_or_empty);
  }
  p["dds"] = nlohmann::json::object();
#ifdef MECHSIM_CYCLONEDDS_VERSION
  p["dds"]["cyclonedds"] = MECHSIM_CYCLONEDDS_VERSION;
#endif
  p["host"] = host_name();
  p["created_utc"] = utc_now_iso8601();
  return p;
}

}  // namespace mechsim::tools

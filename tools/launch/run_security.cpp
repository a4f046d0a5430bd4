#include "run_security.h"

#include <cstdlib>

#include "mechsim/transport/security.h"

namespace mechsim::launch {

namespace {
constexpr const char* kLauncherIdentity = "launcher";  // = security::kLauncherIdentity (tools/security)
}

std::vector<std::string> security_problems(const config::Scene& scene) {
  std::vector<std::string> problems;
  if (scene.security_dir.empty()) return problems;
  std::vector<std::string> names{kLauncherIdentity};
  for (const auto& p : scene.participants) names.push_back(p.name);
  for (const auto& name : names)
    for (const auto& why : transport::security_file_problems({scene.security_dir, name}))
      problems.push_back(scene.file + ": dds.security: " + why + (name == kLauncherIdentity ? "" : " (participant '" + name + "')") +
                         "; make the folder with `mechsim security init " + scene.security_dir + " " + scene.file +
                         "` (docs/security.md)");
  return problems;
}

void configure_security_environment(const config::Scene& scene) {
  if (scene.security_dir.empty()) {
    ::unsetenv(transport::kSecurityDirEnv);
    ::unsetenv(transport::kSecurityIdentityEnv);
    return;
  }
  ::setenv(transport::kSecurityDirEnv, scene.security_dir.c_str(), 1);
  ::setenv(transport::kSecurityIdentityEnv, kLauncherIdentity, 1);
}

std::vector<std::string> node_security_environment(const config::Scene& scene, const std::string& node) {
  if (scene.security_dir.empty()) return {};
  return transport::security_environment({scene.security_dir, node});
}

}  // namespace mechsim::launch

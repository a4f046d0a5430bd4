#include "run_security.h"

#include <cstdlib>
#include <filesystem>

#include "hosts.h"
#include "mechsim/transport/domain_lock.h"
#include "mechsim/transport/security.h"

namespace mechsim::launch {

using transport::kLauncherIdentity;

std::vector<std::string> security_problems(const config::Scene& scene) {
  std::vector<std::string> problems;
  if (scene.security_dir.empty()) return problems;
  std::vector<std::string> names{kLauncherIdentity};
  for (const auto& p : scene.participants) names.push_back(p.name);
  // Cyclone DDS 0.10 and Fast DDS 2.9 do not complete the PKI-DH handshake with each other
  // (docs/security.md#vendors): a mixed secured run would only time out.
  std::string cyclone, fastdds;
  const auto note = [&](const std::string& vendor, const std::string& who) {
    std::string& list = vendor == "fastdds" ? fastdds : cyclone;
    list += (list.empty() ? "" : ", ") + who;
  };
  note(scene.vendor, "the launcher");
  if (scene.record) note("cyclone", "the recorder");  // the raw-CDR recorder is a Cyclone participant
  for (const auto& p : scene.participants) note(p.vendor, p.name);
  const char* allow = std::getenv("MECHSIM_SECURITY_ALLOW_MIXED");
  if (!cyclone.empty() && !fastdds.empty() && !(allow && std::string(allow) == "1"))
    problems.push_back(scene.file + ": dds.security: expected one DDS vendor for the launcher and every participant: Cyclone "
                       "DDS 0.10 and Fast DDS 2.9 do not complete the DDS Security handshake with each other (docs/security.md, "
                       "'Vendors'); got cyclone for " + cyclone + " and fastdds for " + fastdds);
  for (const auto& name : names)
    for (const auto& why : transport::security_file_problems({scene.security_dir, name, scene.security_protection}))
      problems.push_back(scene.file + ": dds.security: " + why + (name == kLauncherIdentity ? "" : " (participant '" + name + "')") +
                         "; make the folder with `mechsim security init " + scene.security_dir + " " + scene.file +
                         "` (docs/security.md)");
  // The governance admits participants only on the domains its rule names: a run on another
  // domain would fail when the launcher's participant is created. (A missing governance is
  // named above.)
  const std::string governance = transport::SecurityIdentity::governance_file(scene.security_dir, scene.security_protection);
  if (std::error_code ec; std::filesystem::is_regular_file(governance, ec)) {
    try {
      const auto ranges = transport::governance_domains(governance);
      const std::string covered = transport::describe(ranges);
      if (scene.domain_id) {
        if (!transport::covers(ranges, *scene.domain_id))
          problems.push_back(scene.file + ": dds.domain: " + std::to_string(*scene.domain_id) +
                             " is not a domain the governance covers (" + covered + ", read from " + governance +
                             "); expected a domain in " + covered + ", or no dds.domain (the launcher picks a free one in " +
                             std::to_string(transport::kFirstFreeDomain) + ".." + std::to_string(transport::kLastFreeDomain) +
                             ")");
      } else {
        for (int d : transport::pickable_domains())
          if (!transport::covers(ranges, d)) {
            problems.push_back(scene.file + ": dds.security: the governance " + governance + " covers domains " + covered +
                               ", not every domain the launcher may pick (in " + std::to_string(transport::kFirstFreeDomain) +
                               ".." + std::to_string(transport::kLastFreeDomain) + ", e.g. " + std::to_string(d) +
                               "); expected dds.domain fixed to one of " + covered);
            break;
          }
      }
    } catch (const std::exception& e) {
      problems.push_back(scene.file + ": dds.security: " + e.what());
    }
  }
  return problems;
}

void configure_security_environment(const config::Scene& scene) {
  if (scene.security_dir.empty()) {
    ::unsetenv(transport::kSecurityDirEnv);
    ::unsetenv(transport::kSecurityIdentityEnv);
    ::unsetenv(transport::kSecurityProtectionEnv);
    return;
  }
  hostrun::set_environment(transport::security_environment({scene.security_dir, kLauncherIdentity, scene.security_protection}));
}

std::vector<std::string> node_security_environment(const config::Scene& scene, const std::string& node) {
  if (scene.security_dir.empty()) return {};
  return transport::security_environment({scene.security_dir, node, scene.security_protection});
}

}  // namespace mechsim::launch

// DDS Security (authentication, access control, encryption) for one participant: where its
// identity lives in a security folder made by `mechsim security init` (docs/security.md),
// and the participant properties that turn the vendor's built-in plugins on. One piece
// serves both backends: each applies the property list it gets here to its participant QoS.
//
// A security folder DIR holds ca.pem (the one CA: identity and permissions CA),
// governance.p7s (signed by the CA) and one folder per identity: DIR/<name>/cert.pem,
// key.pem (mode 0600), permissions.p7s.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mechsim::transport {

// Environment of a secured process: the folder and the identity its participants use.
inline constexpr const char* kSecurityDirEnv = "MECHSIM_DDS_SECURITY";
inline constexpr const char* kSecurityIdentityEnv = "MECHSIM_DDS_IDENTITY";

// Identity names that are not a participant's: the launcher (publishes mechsim/control,
// reads everything; its recorder shares it) and an observer (reads everything: `mechsim
// record`, `mechsim topic`). `mechsim security init` makes both.
inline constexpr const char* kLauncherIdentity = "launcher";
inline constexpr const char* kObserverIdentity = "observer";

struct SecurityIdentity {
  std::string dir;   // the security folder (absolute)
  std::string name;  // a scene participant, "launcher" or "observer"

  std::string ca() const { return dir + "/ca.pem"; }
  std::string governance() const { return dir + "/governance.p7s"; }
  std::string certificate() const { return dir + "/" + name + "/cert.pem"; }
  std::string private_key() const { return dir + "/" + name + "/key.pem"; }
  std::string permissions() const { return dir + "/" + name + "/permissions.p7s"; }
  // The files above, in that order.
  std::vector<std::string> files() const;
};

// The identity named by MECHSIM_DDS_SECURITY and MECHSIM_DDS_IDENTITY; nullopt when neither
// is set. Throws std::runtime_error naming the variable when only one is set.
std::optional<SecurityIdentity> security_from_environment();

// "MECHSIM_DDS_SECURITY=<dir>", "MECHSIM_DDS_IDENTITY=<name>": for a child process.
std::vector<std::string> security_environment(const SecurityIdentity& identity);

// Problems with the identity's files, each naming the file ("<DIR>/servo/key.pem: missing",
// "...: readable by others (mode 0644); expected 0600"). Empty when all is there.
std::vector<std::string> security_file_problems(const SecurityIdentity& identity);

// The participant properties ("dds.sec.*") for the vendor's built-in plugins (PKI-DH
// authentication, permissions access control, AES-GCM-GMAC crypto) with this identity's
// files: the standard names Cyclone DDS reads, or Fast DDS's "builtin.<plugin>." names.
// Throws std::runtime_error naming the file when security_file_problems() finds any, and for
// an unknown vendor.
std::vector<std::pair<std::string, std::string>> security_properties(const SecurityIdentity& identity,
                                                                     const std::string& vendor);

}  // namespace mechsim::transport

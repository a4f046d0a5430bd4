// DDS Security (authentication, access control, encryption) for one participant: where its
// identity lives in a security folder made by `mechsim security init` (docs/security.md),
// and the participant properties that turn the vendor's built-in plugins on. One piece
// serves both backends: each applies the property list it gets here to its participant QoS.
//
// A security folder DIR holds ca.pem (the one CA: identity and permissions CA), two
// governance documents signed by the CA, governance.p7s (everything encrypted) and
// governance_sign.p7s (everything signed, nothing encrypted), and one folder per identity:
// DIR/<name>/cert.pem, key.pem (mode 0600), permissions.p7s. A run's protection (a scene's
// dds.protection) chooses the governance every participant of the run reads.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mechsim::transport {

// Environment of a secured process: the folder and the identity its participants use.
inline constexpr const char* kSecurityDirEnv = "MECHSIM_DDS_SECURITY";
inline constexpr const char* kSecurityIdentityEnv = "MECHSIM_DDS_IDENTITY";
// "encrypt" (the default when unset) or "sign": which governance the participant reads.
inline constexpr const char* kSecurityProtectionEnv = "MECHSIM_DDS_PROTECTION";

// What DDS Security protects in a run (docs/security.md, 'Protection'): both authenticate
// participants and control access; "encrypt" encrypts discovery, submessages and payloads,
// "sign" signs them (GMAC) and leaves them readable on the wire.
inline constexpr const char* kProtectionEncrypt = "encrypt";
inline constexpr const char* kProtectionSign = "sign";

// Identity names that are not a participant's: the launcher (publishes mechsim/control,
// reads everything; its recorder shares it) and an observer (reads everything: `mechsim
// record`, `mechsim topic`). `mechsim security init` makes both.
inline constexpr const char* kLauncherIdentity = "launcher";
inline constexpr const char* kObserverIdentity = "observer";

struct SecurityIdentity {
  std::string dir;   // the security folder (absolute)
  std::string name;  // a scene participant, "launcher" or "observer"
  std::string protection = kProtectionEncrypt;  // kProtectionEncrypt or kProtectionSign

  std::string ca() const { return dir + "/ca.pem"; }
  std::string governance() const { return governance_file(dir, protection); }
  static std::string governance_file(const std::string& dir, const std::string& protection) {
    return dir + (protection == kProtectionSign ? "/governance_sign.p7s" : "/governance.p7s");
  }
  std::string certificate() const { return dir + "/" + name + "/cert.pem"; }
  std::string private_key() const { return dir + "/" + name + "/key.pem"; }
  std::string permissions() const { return dir + "/" + name + "/permissions.p7s"; }
  // The files above, in that order.
  std::vector<std::string> files() const;
};

// The identity named by MECHSIM_DDS_SECURITY and MECHSIM_DDS_IDENTITY (and its protection,
// MECHSIM_DDS_PROTECTION); nullopt when neither is set. Throws std::runtime_error naming
// the variable when only one is set, or the protection is neither encrypt nor sign.
std::optional<SecurityIdentity> security_from_environment();

// "MECHSIM_DDS_SECURITY=<dir>", "MECHSIM_DDS_IDENTITY=<name>", "MECHSIM_DDS_PROTECTION=<p>":
// for a child process.
std::vector<std::string> security_environment(const SecurityIdentity& identity);

// Problems with the identity's files, each naming the file ("<DIR>/servo/key.pem: missing",
// "...: readable by others (mode 0644); expected 0600"). Empty when all is there.
std::vector<std::string> security_file_problems(const SecurityIdentity& identity);

// The domain ids a governance document's rules cover (the <domains> of each
// <domain_rule>: <id> and <id_range>), read from the signed file the participants read (an
// S/MIME message whose first part is the XML in clear text). Throws std::runtime_error
// naming the file when it cannot be read or names no domain.
struct DomainRange {
  int min = 0, max = 0;
};
std::vector<DomainRange> governance_domains(const std::string& governance_file);
bool covers(const std::vector<DomainRange>& ranges, int domain);
// "0..230", "5, 7..9".
std::string describe(const std::vector<DomainRange>& ranges);

// The participant properties ("dds.sec.*") for the vendor's built-in plugins (PKI-DH
// authentication, permissions access control, AES-GCM-GMAC crypto) with this identity's
// files: the standard names Cyclone DDS reads, or Fast DDS's "builtin.<plugin>." names.
// Throws std::runtime_error naming the file when security_file_problems() finds any, and for
// an unknown vendor.
std::vector<std::pair<std::string, std::string>> security_properties(const SecurityIdentity& identity,
                                                                     const std::string& vendor);

}  // namespace mechsim::transport

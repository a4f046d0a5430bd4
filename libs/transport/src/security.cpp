#include "mechsim/transport/security.h"

#include <sys/stat.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <regex>
#include <stdexcept>

namespace mechsim::transport {

std::vector<std::string> SecurityIdentity::files() const {
  return {ca(), governance(), certificate(), private_key(), permissions()};
}

std::optional<SecurityIdentity> security_from_environment() {
  const char* dir = std::getenv(kSecurityDirEnv);
  const char* name = std::getenv(kSecurityIdentityEnv);
  const bool has_dir = dir != nullptr && *dir != '\0';
  const bool has_name = name != nullptr && *name != '\0';
  if (!has_dir && !has_name) return std::nullopt;
  if (!has_dir)
    throw std::runtime_error(std::string(kSecurityIdentityEnv) + " is set but " + kSecurityDirEnv +
                             " is not: expected the security folder of `mechsim security init` (docs/security.md)");
  if (!has_name)
    throw std::runtime_error(std::string(kSecurityDirEnv) + " is set but " + kSecurityIdentityEnv +
                             " is not: expected the identity to use (a participant, launcher or observer; docs/security.md)");
  SecurityIdentity identity{dir, name};
  if (const char* p = std::getenv(kSecurityProtectionEnv); p != nullptr && *p != '\0') {
    identity.protection = p;
    if (identity.protection != kProtectionEncrypt && identity.protection != kProtectionSign)
      throw std::runtime_error(std::string(kSecurityProtectionEnv) + "=" + identity.protection +
                               ": expected encrypt or sign (docs/security.md, 'Protection')");
  }
  return identity;
}

std::vector<std::string> security_environment(const SecurityIdentity& identity) {
  return {std::string(kSecurityDirEnv) + "=" + identity.dir, std::string(kSecurityIdentityEnv) + "=" + identity.name,
          std::string(kSecurityProtectionEnv) + "=" + identity.protection};
}

std::vector<DomainRange> governance_domains(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file + ": cannot read the governance document");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  // DDS Security 9.4.1.2.2: <domains> holds <id>N</id> and <id_range> with <min> and/or <max>
  // (a missing bound is open: up to 232, Cyclone's and Fast DDS's highest domain id).
  static const std::regex domains(R"(<domains>([\s\S]*?)</domains>)");
  static const std::regex item(
      R"(<id>\s*(\d+)\s*</id>|<id_range>\s*(?:<min>\s*(\d+)\s*</min>)?\s*(?:<max>\s*(\d+)\s*</max>)?\s*</id_range>)");
  std::vector<DomainRange> ranges;
  for (std::sregex_iterator d(text.begin(), text.end(), domains), end; d != end; ++d) {
    const std::string inner = (*d)[1].str();
    for (std::sregex_iterator i(inner.begin(), inner.end(), item); i != end; ++i) {
      const auto& m = *i;
      if (m[1].matched) {
        const int id = std::stoi(m[1].str());
        ranges.push_back({id, id});
      } else {
        ranges.push_back({m[2].matched ? std::stoi(m[2].str()) : 0, m[3].matched ? std::stoi(m[3].str()) : 232});
      }
    }
  }
  if (ranges.empty())
    throw std::runtime_error(file + ": names no domain (no <domains> with an <id> or <id_range>); expected the governance of "
                             "`mechsim security init` (docs/security.md)");
  return ranges;
}

bool covers(const std::vector<DomainRange>& ranges, int domain) {
  for (const auto& r : ranges)
    if (domain >= r.min && domain <= r.max) return true;
  return false;
}

std::string describe(const std::vector<DomainRange>& ranges) {
  std::string s;
  for (const auto& r : ranges)
    s += (s.empty() ? "" : ", ") + (r.min == r.max ? std::to_string(r.min) : std::to_string(r.min) + ".." + std::to_string(r.max));
  return s;
}

std::vector<std::string> security_file_problems(const SecurityIdentity& identity) {
  std::vector<std::string> problems;
  for (const std::string& file : identity.files()) {
    struct stat st {};
    if (::stat(file.c_str(), &st) != 0) {
      problems.push_back(file + ": missing");
      continue;
    }
    if (!S_ISREG(st.st_mode)) {
      problems.push_back(file + ": not a regular file");
      continue;
    }
    if (file == identity.private_key() && (st.st_mode & 077) != 0) {
      char mode[8];
      std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(st.st_mode & 0777));
      problems.push_back(file + ": a private key readable by others (mode " + mode + "); expected mode 0600");
    }
  }
  return problems;
}

std::vector<std::pair<std::string, std::string>> security_properties(const SecurityIdentity& identity,
                                                                     const std::string& vendor) {
  if (const auto problems = security_file_problems(identity); !problems.empty())
    throw std::runtime_error("DDS security identity '" + identity.name + "': " + problems.front() +
                             " (make the folder with `mechsim security init`, docs/security.md)");
  const auto uri = [](const std::string& path) { return "file://" + path; };
  if (vendor == "cyclone") {
#ifdef MECHSIM_CYCLONE_SECURITY_DIR
    // The Debian package keeps the plugins in a folder of their own, outside the loader's
    // search path: absolute paths.
    const std::string lib = MECHSIM_CYCLONE_SECURITY_DIR "/libdds_security_";
    return {{"dds.sec.auth.library.path", lib + "auth.so"},
            {"dds.sec.auth.library.init", "init_authentication"},
            {"dds.sec.auth.library.finalize", "finalize_authentication"},
            {"dds.sec.crypto.library.path", lib + "crypto.so"},
            {"dds.sec.crypto.library.init", "init_crypto"},
            {"dds.sec.crypto.library.finalize", "finalize_crypto"},
            {"dds.sec.access.library.path", lib + "ac.so"},
            {"dds.sec.access.library.init", "init_access_control"},
            {"dds.sec.access.library.finalize", "finalize_access_control"},
            {"dds.sec.auth.identity_ca", uri(identity.ca())},
            {"dds.sec.auth.identity_certificate", uri(identity.certificate())},
            {"dds.sec.auth.private_key", uri(identity.private_key())},
            {"dds.sec.access.permissions_ca", uri(identity.ca())},
            {"dds.sec.access.governance", uri(identity.governance())},
            {"dds.sec.access.permissions", uri(identity.permissions())}};
#else
    throw std::runtime_error("Cyclone DDS security: this build found no Cyclone DDS security plugins "
                             "(libdds_security_auth.so) when it was configured");
#endif
  }
  if (vendor == "fastdds") {
    const std::string auth = "dds.sec.auth.builtin.PKI-DH.", access = "dds.sec.access.builtin.Access-Permissions.";
    return {{"dds.sec.auth.plugin", "builtin.PKI-DH"},
            {auth + "identity_ca", uri(identity.ca())},
            {auth + "identity_certificate", uri(identity.certificate())},
            {auth + "private_key", uri(identity.private_key())},
            {"dds.sec.access.plugin", "builtin.Access-Permissions"},
            {access + "permissions_ca", uri(identity.ca())},
            {access + "governance", uri(identity.governance())},
            {access + "permissions", uri(identity.permissions())},
            {"dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC"}};
  }
  throw std::runtime_error("DDS security: no security properties for vendor '" + vendor + "'");
}

}  // namespace mechsim::transport

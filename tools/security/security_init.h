// `mechsim security init DIR SCENE` (docs/security.md): a CA, one certificate and signed
// permissions document per identity, and a signed governance document, made with openssl.
// The identities are the scene's participants (each may publish only its own topics and
// read only its inputs), the launcher (publishes mechsim/control, reads everything: its
// status reader and the run's recorder) and an observer (reads everything, publishes
// nothing: `mechsim record`, `mechsim topic`).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "mechsim/cosim/scene_plan.h"
#include "mechsim/transport/security.h"

namespace mechsim::security {

struct IdentityGrant {
  std::string name;                    // folder DIR/<name>, certificate CN
  std::vector<std::string> publish;    // topic names (DDS Security fnmatch expressions)
  std::vector<std::string> subscribe;
};

// Identity names that are not a participant's (transport/security.h).
using transport::kLauncherIdentity;
using transport::kObserverIdentity;

// The grants a run of `plan` needs: one per participant, the launcher and the observer.
// Throws config::ConfigError when a participant is named like one of the others.
std::vector<IdentityGrant> grants_for_plan(const cosim::ScenePlan& plan);

// The permissions document (XML, unsigned) of one identity.
std::string permissions_xml(const IdentityGrant& grant);
// The governance document (XML, unsigned) for a protection (transport::kProtectionEncrypt
// or kProtectionSign): authentication required on domains 0..230, read and write access
// control on, discovery, liveliness, submessages and payloads of every topic encrypted
// (ENCRYPT), or discovery, liveliness and every RTPS message as a whole signed (SIGN:
// rtps_protection_kind SIGN, metadata and data protection NONE).
std::string governance_xml(const std::string& protection);

// Writes DIR: ca.pem and ca_key.pem (kept when they exist, so identities can be added or
// re-issued under the same CA), governance.p7s and governance_sign.p7s, and DIR/<name>/{cert.pem, key.pem,
// permissions.p7s} for every grant (re-issued). Private keys get mode 0600. Throws
// std::runtime_error naming the file and openssl's message.
void init_security_folder(const std::string& dir, const std::vector<IdentityGrant>& grants, std::ostream& log);

}  // namespace mechsim::security

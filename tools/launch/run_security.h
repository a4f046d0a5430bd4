// DDS Security of a run (a scene's `dds.security`, docs/security.md): every process gets its
// identity from the security folder through its environment (transport/security.h): the
// launcher and its recorder "launcher", each node its participant name.
#pragma once

#include <string>
#include <vector>

#include "mechsim/config/scene.h"

namespace mechsim::launch {

// What a secured run of `scene` would miss, each naming the scene file, the key and the file
// ("scene.yaml: dds.security: /x/sec/servo/cert.pem: missing; make the folder with ...").
// Empty for an unsecured scene or a complete folder.
std::vector<std::string> security_problems(const config::Scene& scene);

// Sets this process's identity ("launcher") for a secured scene; clears an inherited one for
// an unsecured scene, so that what the scene says holds.
void configure_security_environment(const config::Scene& scene);

// The environment entries that give node `node` its identity; none for an unsecured scene.
std::vector<std::string> node_security_environment(const config::Scene& scene, const std::string& node);

}  // namespace mechsim::launch

// `mechsim security init DIR SCENE`: the certificates and signed documents a secured run of
// SCENE needs (docs/security.md).
#include <cstdio>
#include <iostream>
#include <string>

#include "commands.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/scene_plan.h"
#include "security_init.h"

namespace mechsim::tools {

void add_security_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("security", "DDS Security: certificates, permissions and governance (docs/security.md)");
  cmd->require_subcommand(1);
  auto* init = cmd->add_subcommand(
      "init",
      "Make DIR for secured runs of SCENE (`dds: {security: DIR}`): a CA, per participant a certificate, a private key "
      "(mode 0600) and signed permissions to publish its own topics and read its inputs, the same for the launcher and an "
      "observer, and the two signed governance documents (everything encrypted, governance.p7s; everything signed, "
      "governance_sign.p7s: the scene's dds.protection chooses). An existing CA in DIR is kept; the identities are issued anew");
  auto dir = std::make_shared<std::string>();
  auto args = std::make_shared<SceneArgs>();
  init->add_option("DIR", *dir, "security folder to write (created if missing)")->required();
  add_scene_args(init, *args);
  init->callback([dir, args, &exit_code] {
    try {
      config::Scene scene = config::load_scene(args->scene, args->overrides());
      cosim::ScenePlan plan = cosim::ScenePlan::build(scene);
      security::init_security_folder(*dir, security::grants_for_plan(plan), std::cout);
      std::printf("security: %s ready for scene '%s': set `dds: {security: %s}` in the scene (and `protection: sign` for "
                  "signed, unencrypted runs), or launch with --set dds.security=%s\n",
                  dir->c_str(), scene.name.c_str(), dir->c_str(), dir->c_str());
      exit_code = 0;
    } catch (const config::ConfigError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      exit_code = 2;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim security init: %s\n", e.what());
      exit_code = 1;
    }
  });
}

}  // namespace mechsim::tools

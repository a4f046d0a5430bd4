// `mechsim fmu info FILE`: what an FMU is, the first thing to run on a new one, and
// `mechsim fmu export TYPE --scene S --participant P -o F.fmu`: a participant as a
// co-simulation FMU (docs/fmi.md).
#include <cstdio>
#include <memory>

#include "commands.h"
#include "fmu_info.h"
#include "fmu_probe.h"
#include "mechsim/config/scene.h"
#include "mechsim/fmi_export/fmu_writer.h"
#include "json_io.h"
#include "provenance.h"

namespace mechsim::tools {

namespace {

void add_fmu_export_command(CLI::App* fmu, int& exit_code) {
  struct Options {
    fmi_export::ExportRequest request;
    std::string scene;
    std::vector<std::string> sets;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = fmu->add_subcommand(
      "export",
      "write a co-simulation FMU (FMI 2.0 or 3.0) of a scene's participant: its block with the scene's parameters and "
      "its own integrator inside the step (Linux x86-64; the FMU carries what it needs beyond libc and libstdc++)");
  cmd->add_option("type", o->request.type, "the participant's node type (servo_amplifier, tachometer, cam_shaft, ...)")
      ->required();
  cmd->add_option("--scene", o->scene, "the scene (YAML) the participant is taken from")->required()->check(CLI::ExistingFile);
  cmd->add_option("--participant", o->request.participant, "the participant's name in the scene")->required();
  cmd->add_option("-o,--output", o->request.output, "the FMU file to write (.fmu)")->required();
  cmd->add_option("--fmi", o->request.fmi_version, "FMI version: 2 or 3 (default 2)")->check(CLI::IsMember({2, 3}));
  cmd->add_option("--set", o->sets, "override a scene value, repeatable: 'participants.servo.params.position_gain=30 1/s'");
  cmd->add_option("--binary", o->request.binary,
                  "the prebuilt FMU binary to pack (default: mechsim_fmu.so next to this executable, or $MECHSIM_FMU_BINARY)");
  cmd->callback([o, &exit_code] {
    try {
      if (o->request.binary.empty()) o->request.binary = fmi_export::default_fmu_binary();
      if (o->request.binary.empty())
        throw std::runtime_error("no FMU binary found: expected mechsim_fmu.so next to the mechsim executable (build target "
                                 "mechsim_fmu), or give --binary / $MECHSIM_FMU_BINARY");
      const config::Scene scene = config::load_scene(o->scene, o->sets);
      const fmi_export::ExportConfig config = fmi_export::export_config(scene, o->request);
      fmi_export::write_fmu(config, o->request);
      std::printf("wrote %s: participant '%s' (%s) as an FMI %d.0 co-simulation FMU\n", o->request.output.c_str(),
                  config.participant.c_str(), config.type.c_str(), o->request.fmi_version);
      exit_code = 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim fmu export: %s\n", e.what());
      exit_code = 1;
    }
  });
}

}  // namespace

void add_fmu_command(CLI::App& app, int& exit_code) {
  auto* fmu = app.add_subcommand("fmu", "Functional Mock-up Units (FMI 2.0 and 3.0): info, export");
  fmu->require_subcommand(1);

  auto* info = fmu->add_subcommand(
      "info", "FMI version, interfaces and capability flags, variables (causality, type, unit, start), platforms");
  auto file = std::make_shared<std::string>();
  auto json = std::make_shared<std::string>();
  info->add_option("file", *file, "the FMU (.fmu)")->required();
  info->add_option("--json", *json, "write the information as JSON to this file ('-': to stdout, instead of the text)");
  info->callback([file, json, &exit_code] {
    try {
      const fmi::FmuArchive archive(fmi::FmuLabel{*file, ""});
      nlohmann::json j;
      if (!json->empty()) {
        j = fmu_info_json(archive);
        j["schema_version"] = schema_version;
        j["provenance"] = provenance("");
      }
      if (*json == "-") {
        std::fputs((j.dump(2) + "\n").c_str(), stdout);
      } else {
        std::fputs(format_fmu_info(archive).c_str(), stdout);
        if (!json->empty()) write_json_file(*json, j);
      }
      exit_code = 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim fmu info: %s\n", e.what());
      exit_code = 1;
    }
  });

  auto* probe = fmu->add_subcommand(
      "probe", "Instantiate and initialize a scene participant's FMU in this process and say how it went (JSON on stdout); "
               "`mechsim check` and `mechsim launch` run it as a child, so that an FMU's crash is not theirs");
  auto probe_args = std::make_shared<SceneArgs>();
  auto participant = std::make_shared<std::string>();
  auto unpack_dir = std::make_shared<std::string>();
  add_scene_args(probe, *probe_args);
  probe->add_option("--participant", *participant, "the participant played by the FMU")->required();
  probe->add_option("--unpack-dir", *unpack_dir, "unpack the FMU under this folder (default: a temporary one, removed after)");
  probe->callback([probe_args, participant, unpack_dir, &exit_code] {
    exit_code = run_fmu_probe(probe_args->scene, probe_args->overrides(), *participant, *unpack_dir);
  });

  add_fmu_export_command(fmu, exit_code);
}

}  // namespace mechsim::tools

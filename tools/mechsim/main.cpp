// `mechsim`: the command line. Each subcommand lives in its own cmd_*.cpp and registers
// itself here; this file only wires them up.
#include <CLI/CLI.hpp>

#include "commands.h"

int main(int argc, char** argv) {
  CLI::App app{"mechsim: distributed co-simulation of machine mechanisms over DDS.\n"
               "Run `mechsim <command> --help` for a command's options."};
  app.require_subcommand(1);
  app.set_version_flag("--version", mechsim::tools::version_string());
  int exit_code = 0;
  mechsim::tools::add_launch_command(app, exit_code);
  mechsim::tools::add_reference_command(app, exit_code);
  mechsim::tools::add_check_command(app, exit_code);
  mechsim::tools::add_cam_design_command(app, exit_code);
  mechsim::tools::add_motor_bode_command(app, exit_code);
  mechsim::tools::add_slide_modes_command(app, exit_code);
  mechsim::tools::add_cvt_map_command(app, exit_code);
  mechsim::tools::add_record_command(app, exit_code);
  mechsim::tools::add_play_command(app, exit_code);
  mechsim::tools::add_bag_command(app, exit_code);
  mechsim::tools::add_topic_command(app, exit_code);
  mechsim::tools::add_bench_command(app, exit_code);
  mechsim::tools::add_agent_command(app, exit_code);
  mechsim::tools::add_security_command(app, exit_code);
  mechsim::tools::add_fmu_command(app, exit_code);
  mechsim::tools::add_scene_command(app, exit_code);
  mechsim::tools::add_sweep_command(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  return exit_code;
}

// Registration of the `mechsim` subcommands. Each sets `exit_code` when it runs.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace mechsim::tools {

std::string version_string();

// The scene argument and the overrides every scene command accepts (--set and the
// shortcuts --step, --end, --mode, --rtf), turned into "dotted.key=value" overrides.
struct SceneArgs {
  std::string scene;
  std::vector<std::string> sets;
  std::string step, end, mode, rtf;
  std::vector<std::string> overrides() const;
};
void add_scene_args(CLI::App* cmd, SceneArgs& args);

void add_launch_command(CLI::App& app, int& exit_code);
void add_reference_command(CLI::App& app, int& exit_code);
void add_check_command(CLI::App& app, int& exit_code);
void add_cam_design_command(CLI::App& app, int& exit_code);
void add_motor_bode_command(CLI::App& app, int& exit_code);
void add_slide_modes_command(CLI::App& app, int& exit_code);
void add_cvt_map_command(CLI::App& app, int& exit_code);
void add_record_command(CLI::App& app, int& exit_code);
void add_play_command(CLI::App& app, int& exit_code);
void add_bag_command(CLI::App& app, int& exit_code);
void add_topic_command(CLI::App& app, int& exit_code);
// `topic serve`, `bag serve` (cmd_serve.cpp, docs/live.md): registered by the topic and bag commands.
void add_topic_serve_command(CLI::App* topic, int& exit_code);
void add_bag_serve_command(CLI::App* bag, int& exit_code);
void add_bench_command(CLI::App& app, int& exit_code);
void add_agent_command(CLI::App& app, int& exit_code);
void add_security_command(CLI::App& app, int& exit_code);
void add_fmu_command(CLI::App& app, int& exit_code);
void add_scene_command(CLI::App& app, int& exit_code);
void add_sweep_command(CLI::App& app, int& exit_code);

}  // namespace mechsim::tools

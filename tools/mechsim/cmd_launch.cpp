#include "commands.h"
#include "launcher.h"

namespace mechsim::tools {

void add_launch_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "launch", "Run a scene distributed: one process per participant over DDS; compare with the reference");
  auto args = std::make_shared<SceneArgs>();
  auto opt = std::make_shared<launch::LaunchOptions>();
  add_scene_args(cmd, *args);
  cmd->add_option("--json", opt->json_path, "also write the run summary (JSON) to this file");
  cmd->add_option("--runs-dir", opt->runs_dir, "parent folder of the run folders")->capture_default_str();
  cmd->add_flag("!--no-plot", opt->plots, "skip the PNG plot");
  cmd->add_flag("!--no-progress", opt->progress, "no progress line");
  cmd->add_option("--dds", opt->dds_layout,
                  "DDS vendors of this run, overriding the scene: cyclone, fastdds (all participants and the "
                  "launcher on one vendor) or mixed (alternating, the launcher on cyclone)")
      ->check(CLI::IsMember({"cyclone", "fastdds", "mixed"}));
  cmd->add_option("--ready-timeout", opt->ready_timeout_s,
                  "seconds from the processes' start until every node must be ready (a scene of many participants "
                  "on a busy machine needs more: docs/line-shaft.md)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--replay", opt->replays,
                  "NODE=FILE: participant NODE publishes what the MCAP recording FILE holds for its topic, step by "
                  "step in lock-step with the live nodes, instead of computing it (repeatable)");
  cmd->callback([args, opt, &exit_code] {
    opt->scene_path = args->scene;
    opt->overrides = args->overrides();
    exit_code = launch::launch(*opt);
  });
}

}  // namespace mechsim::tools

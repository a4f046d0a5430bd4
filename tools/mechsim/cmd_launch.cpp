#include "commands.h"
#include "launcher.h"
#include "live_server.h"

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
  cmd->add_option("--live", opt->live,
                  "[ADDRESS:]PORT: serve the run live while it goes, Foxglove WebSocket protocol and a browser page "
                  "(loopback unless an address is given; docs/live.md)")
      ->check([](const std::string& text) {
        live::LiveOptions o;
        try {
          live::parse_listen_address(text, o);
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
        return std::string();
      });
  cmd->add_option("--live-rate", opt->live_rate_hz, "with --live: messages per second per channel and client, at most")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 10000.0));
  cmd->callback([args, opt, &exit_code] {
    opt->scene_path = args->scene;
    opt->overrides = args->overrides();
    exit_code = launch::launch(*opt);
  });
}

}  // namespace mechsim::tools

#include <iostream>

#include "commands.h"
#include "stop_signals.h"
#include "sweep.h"

namespace mechsim::tools {

void add_sweep_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "sweep", "A design study: run the scene at every point of a grid or sample design of --vary keys, in process "
               "and in parallel; one table (CSV, JSON) of figures and errors, and plots (docs/sweeps.md)");
  auto args = std::make_shared<SceneArgs>();
  auto opt = std::make_shared<sweep::SweepOptions>();
  auto method = std::make_shared<std::string>("grid");
  add_scene_args(cmd, *args);
  cmd->add_option("--vary", opt->vary,
                  "KEY=SPEC, repeatable, for any key --set takes: a list 'a,b,c' ('follower.spring.preload=100 N,150 N'), "
                  "'lo..hi:n' or 'lo..hi:n:log' with units as in scenes ('servo.position_gain=20..80 1/s:7')")
      ->required();
  cmd->add_option("--method", *method, "grid (every combination), lhs (Latin hypercube) or random")
      ->capture_default_str()
      ->check(CLI::IsMember({"grid", "lhs", "random"}));
  cmd->add_option("--samples", opt->design.samples, "points of an lhs or random design");
  cmd->add_option("--seed", opt->design.seed, "seed of an lhs or random design")->capture_default_str();
  cmd->add_option("--jobs", opt->jobs, "points run at a time (default: the machine's cores)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--out", opt->out_dir, "folder of the table, plots and points")->capture_default_str();
  cmd->add_flag("--resume", opt->resume, "take the points already finished in --out instead of running them again");
  cmd->add_flag("!--no-plot", opt->plots, "skip the PNG plots");
  cmd->add_flag("!--no-progress", opt->progress, "no progress line");
  cmd->add_option("--max-hours", opt->max_hours, "stop after the first points when the estimate is longer")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->callback([args, opt, method, &exit_code] {
    opt->scene_path = args->scene;
    opt->overrides = args->overrides();
    opt->design.method = sweep::parse_method(*method);
    catch_stop_signals();
    exit_code = sweep::run_sweep(*opt, std::cout);
  });
}

}  // namespace mechsim::tools

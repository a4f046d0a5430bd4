// `mechsim scene stations`: writes a scene of a generated family (docs/line-shaft.md).
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>

#include "commands.h"
#include "line_shaft_scene.h"

namespace mechsim::tools {

void add_scene_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("scene", "Write a generated scene (a family of scenes with a size parameter)");
  cmd->require_subcommand(1);
  auto* stations = cmd->add_subcommand(
      "stations", "The press line with K cam stations on one line shaft, elastic segments between them "
                  "(docs/line-shaft.md); 1 + 2 K participants");
  struct Args {
    LineShaftOptions options;
    std::string output;
  };
  auto args = std::make_shared<Args>();
  stations->add_option("--stations,-K", args->options.stations, "number of cam stations K, 1.." + std::to_string(kMaxStations))
      ->required();
  stations->add_option("-o,--output", args->output, "scene file to write (default: standard output)");
  stations->add_option("--stiffness", args->options.segment_stiffness, "torsional stiffness of each segment, N m/rad")
      ->capture_default_str();
  stations->add_option("--damping", args->options.segment_damping, "damping of each segment, N m s/rad")
      ->capture_default_str();
  stations->callback([args, &exit_code] {
    std::string text;
    try {
      text = line_shaft_scene(args->options);
    } catch (const std::invalid_argument& e) {
      std::fprintf(stderr, "mechsim scene stations: %s\n", e.what());
      exit_code = 2;
      return;
    }
    if (args->output.empty()) {
      std::fputs(text.c_str(), stdout);
      return;
    }
    std::ofstream out(args->output);
    out << text;
    if (!out.flush()) {
      std::fprintf(stderr, "mechsim scene stations: cannot write %s\n", args->output.c_str());
      exit_code = 1;
      return;
    }
    std::fprintf(stderr, "mechsim scene stations: wrote %s (%d stations)\n", args->output.c_str(), args->options.stations);
  });
}

}  // namespace mechsim::tools

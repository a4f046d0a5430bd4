// `mechsim fmu info FILE`: what an FMU is, the first thing to run on a new one (docs/fmi.md).
#include <cstdio>
#include <memory>

#include "commands.h"
#include "fmu_info.h"
#include "json_io.h"
#include "provenance.h"

namespace mechsim::tools {

void add_fmu_command(CLI::App& app, int& exit_code) {
  auto* fmu = app.add_subcommand("fmu", "Functional Mock-up Units (FMI 2.0 and 3.0): info");
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
}

}  // namespace mechsim::tools

// `mechsim bag info FILE`, `mechsim bag export FILE --csv DIR`: what a recording holds, and
// its samples decoded into one CSV per topic.
#include <cstdio>

#include "bag_inspect.h"
#include "commands.h"
#include "json_io.h"
#include "provenance.h"

namespace mechsim::tools {

void add_bag_command(CLI::App& app, int& exit_code) {
  auto* bag = app.add_subcommand("bag", "Inspect MCAP recordings: info, export");
  bag->require_subcommand(1);

  auto* info = bag->add_subcommand("info", "Topics, types, counts, time ranges, sizes, compression, complete or truncated");
  auto info_file = std::make_shared<std::string>();
  auto info_json = std::make_shared<std::string>();
  info->add_option("file", *info_file, "the recording (.mcap)")->required();
  info->add_option("--json", *info_json, "also write the information as JSON");
  info->callback([info_file, info_json, &exit_code] {
    try {
      const recorder::BagInfo bi = recorder::inspect_bag(*info_file);
      std::fputs(recorder::format_bag_info(bi).c_str(), stdout);
      if (!info_json->empty()) {
        nlohmann::json j = recorder::to_json(bi);
        j["schema_version"] = schema_version;
        j["provenance"] = provenance("");
        write_json_file(*info_json, j);
      }
      exit_code = 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim bag info: %s\n", e.what());
      exit_code = 1;
    }
  });

  auto* exp = bag->add_subcommand("export", "Write one CSV per topic: t, step, run_id and the IDL fields");
  auto exp_file = std::make_shared<std::string>();
  auto exp_dir = std::make_shared<std::string>();
  exp->add_option("file", *exp_file, "the recording (.mcap)")->required();
  exp->add_option("--csv", *exp_dir, "folder for the CSV files (created)")->required();
  exp->callback([exp_file, exp_dir, &exit_code] {
    try {
      for (const auto& t : recorder::export_csv(*exp_file, *exp_dir)) {
        if (t.file.empty())
          std::printf("  %-24s skipped: no decoder for its type\n", t.topic.c_str());
        else
          std::printf("  %-24s %8llu rows  %s%s\n", t.topic.c_str(), static_cast<unsigned long long>(t.rows), t.file.c_str(),
                      t.skipped ? (" (" + std::to_string(t.skipped) + " undecodable skipped)").c_str() : "");
      }
      exit_code = 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim bag export: %s\n", e.what());
      exit_code = 1;
    }
  });
}

}  // namespace mechsim::tools

// `mechsim bag info FILE`, `mechsim bag export FILE --csv DIR`: what a recording holds, and
// its samples decoded into one CSV per topic (and `bag serve`: cmd_serve.cpp).
#include <cstdint>
#include <cstdio>
#include <memory>

#include "bag_inspect.h"
#include "commands.h"
#include "json_io.h"
#include "provenance.h"

namespace mechsim::tools {

namespace {

// --strict and --max-chunk-mib, shared by info and export.
void add_read_options(CLI::App* cmd, const std::shared_ptr<recorder::BagReadOptions>& options) {
  cmd->add_flag("--strict", options->strict,
                "refuse a file with any problem (default: skip damaged chunks, read the sound ones)");
  cmd->add_option_function<std::uint64_t>(
         "--max-chunk-mib", [options](std::uint64_t mib) { options->limits.max_chunk_size = mib << 20; },
         "largest uncompressed chunk accepted, MiB (default 64; the recorder writes 1 MiB chunks)")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{4095}));
}

}  // namespace

void add_bag_command(CLI::App& app, int& exit_code) {
  auto* bag = app.add_subcommand("bag", "Inspect MCAP recordings: info, export, serve");
  bag->require_subcommand(1);

  auto* info = bag->add_subcommand("info", "Topics, types, counts, time ranges, sizes, compression, complete or truncated");
  auto info_file = std::make_shared<std::string>();
  auto info_json = std::make_shared<std::string>();
  info->add_option("file", *info_file, "the recording (.mcap)")->required();
  info->add_option("--json", *info_json, "also write the information as JSON");
  auto info_options = std::make_shared<recorder::BagReadOptions>();
  add_read_options(info, info_options);
  info->callback([info_file, info_json, info_options, &exit_code] {
    try {
      const recorder::BagInfo bi = recorder::inspect_bag(*info_file, *info_options);
      std::fputs(recorder::format_bag_info(bi).c_str(), stdout);
      if (!info_json->empty()) {
        nlohmann::json j = recorder::to_json(bi);
        j["schema_version"] = schema_version;
        j["provenance"] = provenance("");
        write_json_file(*info_json, j);
      }
      exit_code = recorder::exit_code(bi);
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
  auto exp_options = std::make_shared<recorder::BagReadOptions>();
  add_read_options(exp, exp_options);
  exp->callback([exp_file, exp_dir, exp_options, &exit_code] {
    try {
      const recorder::BagExport result = recorder::export_csv(*exp_file, *exp_dir, *exp_options);
      for (const auto& t : result.topics) {
        if (t.file.empty())
          std::printf("  %-24s skipped: no decoder for its type\n", t.topic.c_str());
        else
          std::printf("  %-24s %8llu rows  %s%s\n", t.topic.c_str(), static_cast<unsigned long long>(t.rows), t.file.c_str(),
                      t.skipped ? (" (" + std::to_string(t.skipped) + " undecodable skipped)").c_str() : "");
      }
      for (const auto& why : result.skipped_chunks) std::fprintf(stderr, "mechsim bag export: skipped: %s\n", why.c_str());
      exit_code = recorder::exit_code(result);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim bag export: %s\n", e.what());
      exit_code = 1;
    }
  });

  add_bag_serve_command(bag, exit_code);
}

}  // namespace mechsim::tools

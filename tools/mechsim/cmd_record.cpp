// `mechsim record`: records a DDS domain into an MCAP file until Ctrl-C / SIGTERM (or
// --duration), closes it cleanly and prints what it recorded per topic. `--recover`
// rebuilds a recording that was cut short (a crash of the recorder) into a complete file.
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "commands.h"
#include "json_io.h"
#include "mechsim/record/mcap_recover.h"
#include "mechsim/record/mcap_types.h"
#include "install_paths.h"
#include "provenance.h"
#include "stop_signals.h"
#include "recorder.h"

namespace mechsim::tools {

namespace {

struct RecordArgs {
  int domain = -1;
  std::vector<std::string> topics;
  std::string regex;
  std::string output;
  std::string compression = "zstd";
  double duration_s = 0.0;
  bool data_sync = false;
  std::string recover;
  std::string json_path;
};

std::string default_recovered_name(const std::string& in) {
  std::filesystem::path p(in);
  return (p.parent_path() / (p.stem().string() + ".recovered.mcap")).string();
}

int recover_file(const RecordArgs& a) {
  const std::string out = a.output.empty() ? default_recovered_name(a.recover) : a.output;
  if (std::filesystem::exists(out) && std::filesystem::equivalent(out, a.recover)) {
    std::fprintf(stderr, "mechsim record --recover: the output must differ from the input\n");
    return 2;
  }
  try {
    const record::RecoveryReport r = record::recover(a.recover, out);
    std::printf("%s: %s, %llu of %llu bytes readable (%s)\n", a.recover.c_str(),
                r.input_complete ? "was complete" : "was truncated", static_cast<unsigned long long>(r.scan_end),
                static_cast<unsigned long long>(r.input_size), r.stop_reason.c_str());
    std::printf("%s: written with %llu schemas, %llu channels, %llu chunks, %llu messages%s\n", out.c_str(),
                static_cast<unsigned long long>(r.schemas), static_cast<unsigned long long>(r.channels),
                static_cast<unsigned long long>(r.chunks), static_cast<unsigned long long>(r.messages),
                r.chunks_dropped ? (", " + std::to_string(r.chunks_dropped) + " damaged chunks dropped").c_str() : "");
    for (const auto& why : r.dropped) std::printf("  not kept: %s\n", why.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim record --recover: %s\n", e.what());
    return 1;
  }
}

void print_report(const recorder::RecordingReport& r, int domain) {
  std::printf("recorded domain %d for %.1f s: %llu messages on %zu topics, %llu bytes in %s\n", domain, r.wall_time_s,
              static_cast<unsigned long long>(r.messages), r.topics.size(), static_cast<unsigned long long>(r.bytes),
              r.file.c_str());
  std::size_t width = 5;
  for (const auto& t : r.topics) width = std::max(width, t.topic.size());
  for (const auto& t : r.topics) {
    std::printf("  %-*s  %-28s %9llu", static_cast<int>(width), t.topic.c_str(), t.type.c_str(),
                static_cast<unsigned long long>(t.samples));
    if (!t.reliable) std::printf("  (best effort: %llu reported lost)", static_cast<unsigned long long>(t.lost));
    std::printf("\n");
  }
}

nlohmann::json report_json(const recorder::RecordingReport& r, int domain) {
  nlohmann::json topics = nlohmann::json::array();
  for (const auto& t : r.topics)
    topics.push_back({{"topic", t.topic}, {"type", t.type}, {"reliable", t.reliable}, {"samples", t.samples}, {"lost", t.lost}});
  return {{"schema_version", schema_version}, {"provenance", provenance("")}, {"domain_id", domain},
          {"file", r.file}, {"messages", r.messages}, {"bytes", r.bytes}, {"wall_time_s", r.wall_time_s},
          {"topics", topics}, {"error", r.error}};
}

int record(const RecordArgs& a) {
  if (a.domain < 0 || a.domain > 232) {
    std::fprintf(stderr, "mechsim record: --domain 0..232 is required (the launcher prints a run's domain)\n");
    return 2;
  }
  if (a.output.empty()) {
    std::fprintf(stderr, "mechsim record: -o FILE is required\n");
    return 2;
  }
  recorder::RecordOptions o;
  o.file = a.output;
  // "name:Type" subscribes at once, before any writer of the topic exists.
  for (const auto& t : a.topics) {
    const auto colon = t.find(':');
    if (colon == std::string::npos || t.compare(colon, 2, "::") == 0) {
      o.topics.names.push_back(t);
    } else {
      o.topics.names.push_back(t.substr(0, colon));
      o.topic_types[t.substr(0, colon)] = t.substr(colon + 1);
    }
  }
  o.topics.regex = a.regex;
  o.sync = a.data_sync ? record::SyncMode::data_sync : record::SyncMode::flush;
  std::unique_ptr<recorder::Recorder> rec;
  try {
    o.compression = recorder::parse_compression(a.compression);
    hostrun::configure_dds_environment();
    catch_stop_signals();
    rec = recorder::start_recording(a.domain, o);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "mechsim record: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim record: %s\n", e.what());
    return 1;
  }
  const bool tty = ::isatty(STDERR_FILENO);
  std::fprintf(stderr, "mechsim: recording domain %d to %s (%s); Ctrl-C stops\n", a.domain, a.output.c_str(),
               a.compression.c_str());
  const auto started = std::chrono::steady_clock::now();
  auto last_progress = started;
  while (!stop_requested()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const auto now = std::chrono::steady_clock::now();
    if (a.duration_s > 0 && std::chrono::duration<double>(now - started).count() >= a.duration_s) break;
    if (tty && now - last_progress > std::chrono::seconds(1)) {
      std::uint64_t n = 0;
      const auto counts = rec->counts();
      for (const auto& t : counts) n += t.samples;
      std::fprintf(stderr, "\rrecording: %llu messages on %zu topics   ", static_cast<unsigned long long>(n), counts.size());
      last_progress = now;
    }
  }
  if (tty) std::fprintf(stderr, "\n");
  const recorder::RecordingReport report = rec->stop();
  print_report(report, a.domain);
  if (!a.json_path.empty()) write_json_file(a.json_path, report_json(report, a.domain));
  if (!report.error.empty()) {
    std::fprintf(stderr, "mechsim record: stopped early: %s\n", report.error.c_str());
    return 1;
  }
  return 0;
}

}  // namespace

void add_record_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("record", "Record DDS topics of a domain into an MCAP file (until Ctrl-C), or --recover one");
  auto a = std::make_shared<RecordArgs>();
  cmd->add_option("--domain", a->domain, "DDS domain id of the run (the launcher prints it)");
  cmd->add_option("--topics", a->topics,
                  "topics to record, comma separated (default: every mechsim topic); NAME:TYPE (e.g. cam/state:CamState) "
                  "subscribes before the topic's writer appears")
      ->delimiter(',');
  cmd->add_option("--regex", a->regex, "record the topics whose whole name matches this regex")->excludes("--topics");
  cmd->add_option("-o,--output", a->output, "the MCAP file to write (with --recover: the rebuilt file)");
  cmd->add_option("--compression", a->compression, "chunk compression")
      ->check(CLI::IsMember({"zstd", "lz4", "none"}))
      ->capture_default_str();
  cmd->add_option("--duration", a->duration_s, "stop after this many seconds (default: until Ctrl-C or SIGTERM)");
  cmd->add_flag("--fsync", a->data_sync, "fdatasync after every chunk (survives a power loss, costs a few ms a chunk)");
  cmd->add_option("--json", a->json_path, "also write the per-topic counts as JSON");
  cmd->add_option("--recover", a->recover, "rebuild this truncated recording into a complete one (-o, default <name>.recovered.mcap)");
  cmd->callback([a, &exit_code] { exit_code = a->recover.empty() ? record(*a) : recover_file(*a); });
}

}  // namespace mechsim::tools

// `mechsim play FILE`: publishes a recording's topics again on a DDS domain (player.h).
#include <unistd.h>

#include <cstdio>
#include <limits>

#include "commands.h"
#include "install_paths.h"
#include "player.h"
#include "stop_signals.h"

namespace mechsim::tools {

namespace {

struct PlayArgs {
  std::string file;
  int domain = -1;
  std::vector<std::string> topics;
  std::string regex;
  double rate = 1.0;
  bool loop = false;
  double start = -std::numeric_limits<double>::infinity();
  double end = std::numeric_limits<double>::infinity();
  double wait_readers_s = 2.0;
};

int play(const PlayArgs& a) {
  if (a.domain < 0 || a.domain > 232) {
    std::fprintf(stderr, "mechsim play: --domain 0..232 is required\n");
    return 2;
  }
  recorder::PlayOptions o;
  o.file = a.file;
  o.topics.names = a.topics;
  o.topics.regex = a.regex;
  o.rate = a.rate;
  o.loop = a.loop;
  o.start_s = a.start;
  o.end_s = a.end;
  o.wait_for_readers = std::chrono::milliseconds(static_cast<long>(a.wait_readers_s * 1e3));
  o.stop = &stop_requested();
  const bool tty = ::isatty(STDERR_FILENO);
  if (tty)
    o.progress = [](double t, std::uint64_t n) {
      std::fprintf(stderr, "\rplaying: t = %.4f s, %llu samples   ", t, static_cast<unsigned long long>(n));
    };
  catch_stop_signals();
  try {
    hostrun::configure_dds_environment();
    const recorder::PlayReport r = recorder::play(a.domain, o);
    if (tty) std::fprintf(stderr, "\n");
    std::printf("played %s on domain %d: %llu samples in %.2f s (%d pass%s%s)\n", a.file.c_str(), a.domain,
                static_cast<unsigned long long>(r.total), r.wall_time_s, r.loops, r.loops == 1 ? "" : "es",
                r.stopped ? ", stopped" : "");
    for (const auto& [topic, n] : r.published) std::printf("  %-32s %9llu\n", topic.c_str(), static_cast<unsigned long long>(n));
    return 0;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "mechsim play: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim play: %s\n", e.what());
    return 1;
  }
}

}  // namespace

void add_play_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "play",
      "Publish the topics of an MCAP recording again on a DDS domain, paced to the clock (--rate) or unpaced. "
      "To stand in for a participant of a live run, use `mechsim launch --replay NODE=FILE`");
  auto a = std::make_shared<PlayArgs>();
  cmd->add_option("file", a->file, "the MCAP recording")->required()->check(CLI::ExistingFile);
  cmd->add_option("--domain", a->domain, "DDS domain id to publish on")->required();
  cmd->add_option("--topics", a->topics,
                  "topics to play, comma separated (default: every recorded data topic; mechsim/control and "
                  "mechsim/status only when named)")
      ->delimiter(',');
  cmd->add_option("--regex", a->regex, "play the topics whose whole name matches this regex")->excludes("--topics");
  cmd->add_option("--rate", a->rate, "speed as a multiple of real time; 0 = as fast as the readers take the samples")
      ->capture_default_str();
  cmd->add_flag("--loop", a->loop, "start over at the end, until Ctrl-C");
  cmd->add_option("--start", a->start, "play from this simulated time [s]");
  cmd->add_option("--end", a->end, "play up to this simulated time [s]");
  cmd->add_option("--wait-readers", a->wait_readers_s, "seconds to wait for readers before the first sample")
      ->capture_default_str();
  cmd->callback([a, &exit_code] { exit_code = play(*a); });
}

}  // namespace mechsim::tools

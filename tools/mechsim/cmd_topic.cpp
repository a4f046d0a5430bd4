// `mechsim topic list|echo|hz` (and `serve`: cmd_serve.cpp): what is on a DDS domain, the samples of one topic decoded
// (YAML-like), and its rate. Samples are read raw and decoded with the recorder's CDR
// decoder, so these commands show exactly what a recording would hold.
//
// echo and hz read data topics with the topics' own QoS (reliable, keep all), like any
// other subscriber: a reader that cannot keep up slows the run down rather than miss steps.
#include <chrono>
#include <cstdio>
#include <optional>
#include <thread>

#include "elapsed.h"
#include "cdr_decoder.h"
#include "commands.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/transport/raw.h"
#include "install_paths.h"
#include "stop_signals.h"

namespace mechsim::tools {

namespace {

using Clock = std::chrono::steady_clock;

bool valid_domain(int domain, const char* cmd) {
  if (domain >= 0 && domain <= 232) return true;
  std::fprintf(stderr, "mechsim topic %s: --domain 0..232 is required (the launcher prints a run's domain)\n", cmd);
  return false;
}

std::unique_ptr<transport::RawParticipant> join(int domain) {
  hostrun::configure_dds_environment();
  catch_stop_signals();
  return transport::create_raw_participant("cyclone", domain);
}

// The type of `topic`: given, fixed (control, status), or announced by a writer on the
// domain (waits for one until Ctrl-C or the timeout). "" when none appeared.
std::string resolve_type(transport::RawParticipant& p, const std::string& topic, const std::string& given,
                         double timeout_s) {
  if (!given.empty()) return transport::scoped_type_name(given);
  if (topic == transport::kControlTopic) return "mechsim::msg::Control";
  if (topic == transport::kStatusTopic) return "mechsim::msg::Status";
  const auto start = Clock::now();
  bool told = false;
  while (!stop_requested() && (timeout_s <= 0 || seconds_since(start) < timeout_s)) {
    for (const auto& t : p.discovered_topics())
      if (t.name == topic && t.publishers > 0) return t.type_name;
    if (!told && seconds_since(start) > 1.0) {
      std::fprintf(stderr, "waiting for a writer of '%s'...\n", topic.c_str());
      told = true;
    }
    p.wait(std::chrono::milliseconds(50));
  }
  return "";
}

struct EndpointArgs {
  std::string topic;
  int domain = -1;
  std::string type;
  double timeout_s = 0.0;
  std::string scene;  // echo: the run's scene, for an FMU participant's variable names
};

void add_endpoint_options(CLI::App* cmd, EndpointArgs& a) {
  cmd->add_option("topic", a.topic, "topic name, e.g. cam/state")->required();
  cmd->add_option("--domain", a.domain, "DDS domain id of the run (the launcher prints it)")->required();
  cmd->add_option("--type", a.type, "IDL type (default: as a writer on the domain announces it)");
  cmd->add_option("--timeout", a.timeout_s, "give up after this many seconds without a writer (default: wait)");
}

// Subscribes to the topic, or prints why not and returns nullptr.
std::unique_ptr<transport::RawReader> subscribe(transport::RawParticipant& p, const EndpointArgs& a, const char* cmd,
                                                const recorder::MessageLayout*& layout) {
  const std::string type = resolve_type(p, a.topic, a.type, a.timeout_s);
  if (type.empty()) {
    if (!stop_requested()) std::fprintf(stderr, "mechsim topic %s: no writer of '%s' on domain %d\n", cmd, a.topic.c_str(), a.domain);
    return nullptr;
  }
  layout = recorder::find_layout(type);
  if (!layout) {
    std::fprintf(stderr, "mechsim topic %s: '%s' has type %s, which mechsim cannot decode\n", cmd, a.topic.c_str(),
                 type.c_str());
    return nullptr;
  }
  return p.create_reader(a.topic, layout->type_name);
}

int list_topics(int domain, double wait_s) {
  if (!valid_domain(domain, "list")) return 2;
  auto p = join(domain);
  // Discovery on loopback takes tens of ms; give it the time asked for.
  const auto start = Clock::now();
  while (!stop_requested() && seconds_since(start) < wait_s) p->wait(std::chrono::milliseconds(50));
  const auto topics = p->discovered_topics();
  std::size_t w_topic = 5, w_type = 4;
  for (const auto& t : topics) {
    w_topic = std::max(w_topic, t.name.size());
    w_type = std::max(w_type, t.type_name.size());
  }
  std::printf("%-*s  %-*s  %4s  %4s\n", static_cast<int>(w_topic), "TOPIC", static_cast<int>(w_type), "TYPE", "PUB", "SUB");
  for (const auto& t : topics)
    std::printf("%-*s  %-*s  %4d  %4d\n", static_cast<int>(w_topic), t.name.c_str(), static_cast<int>(w_type),
                t.type_name.c_str(), t.publishers, t.subscribers);
  if (topics.empty()) std::fprintf(stderr, "no topics on domain %d\n", domain);
  return 0;
}

void print_sample(const std::string& topic, const recorder::MessageLayout& layout, const recorder::DecodedSample& s) {
  std::printf("--- # %s (%s)\nrun_id: 0x%016llx\nstep: %llu\nt: %s\n", topic.c_str(), layout.type_name.c_str(),
              static_cast<unsigned long long>(s.header.run_id), static_cast<unsigned long long>(s.header.step),
              recorder::to_text(s.header.t).c_str());
  for (std::size_t i = 0; i < layout.fields.size(); ++i) {
    const bool text = layout.fields[i].kind == recorder::CdrKind::string;
    std::string v = recorder::to_text(s.values[i]);
    if (text) {  // YAML double-quoted scalar
      std::string q = "\"";
      for (char c : v) q += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
      v = q + "\"";
    }
    std::printf("%s: %s\n", layout.fields[i].name.c_str(), v.c_str());
  }
  std::fflush(stdout);
}

// An FMU participant's topic (FmuOutputs) has no names on the wire: with --scene they are
// its FMU's output variables, from the scene's plan; without, reals[i], integers[i], ...
std::optional<recorder::MessageLayout> fmu_names(const EndpointArgs& a) {
  if (a.scene.empty()) return std::nullopt;
  const config::Scene scene = config::load_scene(a.scene);
  const cosim::ScenePlan plan = cosim::ScenePlan::build(scene);
  for (const auto& node : plan.nodes())
    if (node.topic == a.topic) return recorder::layout_of(*node.type->publishes);
  throw std::invalid_argument(a.scene + ": no participant publishes '" + a.topic + "'");
}

int echo(const EndpointArgs& a, long count) {
  if (!valid_domain(a.domain, "echo")) return 2;
  std::optional<recorder::MessageLayout> named;
  try {
    named = fmu_names(a);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim topic echo: %s\n", e.what());
    return 2;
  }
  auto p = join(a.domain);
  const recorder::MessageLayout* layout = nullptr;
  auto reader = subscribe(*p, a, "echo", layout);
  if (!reader) return stop_requested() ? 0 : 1;
  std::optional<recorder::MessageLayout> unnamed;
  if (layout->sequences) {
    if (named && named->type_name == layout->type_name) layout = &*named;
  }
  transport::RawSample sample;
  long shown = 0;
  while (!stop_requested() && (count <= 0 || shown < count)) {
    if (!reader->take(sample)) {
      p->wait(std::chrono::milliseconds(100));
      continue;
    }
    try {
      if (layout->sequences && layout->fields.empty()) {  // no names: as many as the sample carries
        unnamed = recorder::unnamed_fmu_layout(sample.cdr);
        print_sample(a.topic, *unnamed, recorder::decode_sample(sample.cdr, *unnamed));
        ++shown;
        continue;
      }
      print_sample(a.topic, *layout, recorder::decode_sample(sample.cdr, *layout));
    } catch (const recorder::CdrError& e) {
      std::printf("--- # %s: undecodable sample of %zu bytes: %s\n", a.topic.c_str(), sample.cdr.size(), e.what());
    }
    ++shown;
  }
  return 0;
}

int hz(const EndpointArgs& a, double window_s, long windows) {
  if (!valid_domain(a.domain, "hz")) return 2;
  if (window_s <= 0) {
    std::fprintf(stderr, "mechsim topic hz: --window must be positive\n");
    return 2;
  }
  auto p = join(a.domain);
  const recorder::MessageLayout* layout = nullptr;
  auto reader = subscribe(*p, a, "hz", layout);
  if (!reader) return stop_requested() ? 0 : 1;
  transport::RawSample sample;
  long printed = 0;
  auto window_start = Clock::now();
  long n = 0;
  double t_first = 0, t_last = 0;
  while (!stop_requested() && (windows <= 0 || printed < windows)) {
    while (reader->take(sample)) {
      if (n == 0) t_first = sample.header.t;
      t_last = sample.header.t;
      ++n;
    }
    const double elapsed = seconds_since(window_start);
    if (elapsed >= window_s) {
      if (n == 0) {
        std::printf("%s: no samples in %.3f s\n", a.topic.c_str(), elapsed);
      } else {
        // Simulated seconds per wall second over the window: the run's real-time factor
        // as this topic sees it.
        std::printf("%s: %.1f Hz (%ld samples in %.3f s), simulated t %.6f .. %.6f s (%.3f s/s)\n", a.topic.c_str(),
                    static_cast<double>(n) / elapsed, n, elapsed, t_first, t_last, (t_last - t_first) / elapsed);
      }
      std::fflush(stdout);
      ++printed;
      n = 0;
      window_start = Clock::now();
      continue;
    }
    const double left = window_s - elapsed;
    p->wait(std::chrono::nanoseconds(static_cast<std::int64_t>(std::min(left, 0.1) * 1e9)));
  }
  return 0;
}

}  // namespace

void add_topic_command(CLI::App& app, int& exit_code) {
  auto* topic = app.add_subcommand("topic", "Topics on a DDS domain: list, echo, hz, serve");
  topic->require_subcommand(1);

  auto* list = topic->add_subcommand("list", "Topics with their type and publisher/subscriber counts");
  auto list_domain = std::make_shared<int>(-1);
  auto list_wait = std::make_shared<double>(1.0);
  list->add_option("--domain", *list_domain, "DDS domain id (the launcher prints a run's domain)")->required();
  list->add_option("--wait", *list_wait, "seconds to listen for discovery before listing")->capture_default_str();
  list->callback([list_domain, list_wait, &exit_code] { exit_code = list_topics(*list_domain, *list_wait); });

  auto* echo_cmd = topic->add_subcommand("echo", "Print the samples of a topic, decoded (YAML-like)");
  auto echo_args = std::make_shared<EndpointArgs>();
  auto echo_count = std::make_shared<long>(0);
  add_endpoint_options(echo_cmd, *echo_args);
  echo_cmd->add_option("--count", *echo_count, "stop after this many samples (default: until Ctrl-C)");
  echo_cmd->add_option("--scene", echo_args->scene,
                       "the run's scene: an FMU participant's topic (FmuOutputs) is printed with its FMU's variable names "
                       "(without: reals[i], integers[i], booleans[i])");
  echo_cmd->callback([echo_args, echo_count, &exit_code] { exit_code = echo(*echo_args, *echo_count); });

  auto* hz_cmd = topic->add_subcommand("hz", "Rate of a topic per window, with the sample count behind it");
  auto hz_args = std::make_shared<EndpointArgs>();
  auto hz_window = std::make_shared<double>(1.0);
  auto hz_windows = std::make_shared<long>(0);
  add_endpoint_options(hz_cmd, *hz_args);
  hz_cmd->add_option("--window", *hz_window, "window length in seconds")->capture_default_str();
  hz_cmd->add_option("--count", *hz_windows, "stop after this many windows (default: until Ctrl-C)");
  hz_cmd->callback([hz_args, hz_window, hz_windows, &exit_code] { exit_code = hz(*hz_args, *hz_window, *hz_windows); });

  add_topic_serve_command(topic, exit_code);
}

}  // namespace mechsim::tools

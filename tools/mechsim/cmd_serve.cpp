// `mechsim topic serve [ADDRESS:]PORT --domain N` and `mechsim bag serve FILE
// [ADDRESS:]PORT`: the live server (tools/live, docs/live.md) on a running domain or a
// recording, until Ctrl-C. `mechsim launch --live` is the third way (cmd_launch.cpp).
#include <chrono>
#include <cstdio>
#include <thread>

#include "bag_source.h"
#include "cdr_decoder.h"
#include "commands.h"
#include "domain_source.h"
#include "install_paths.h"
#include "live_server.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/scene_plan.h"
#include "stop_signals.h"

namespace mechsim::tools {

namespace {

struct ServeArgs {
  std::string listen = "8765";
  double rate_hz = 60.0;
  std::size_t max_clients = 8;
};

void add_serve_options(CLI::App* cmd, ServeArgs& a) {
  cmd->add_option("listen", a.listen,
                  "[ADDRESS:]PORT to listen on (default 8765 on loopback; 0.0.0.0:PORT serves every interface)")
      ->capture_default_str();
  cmd->add_option("--live-rate", a.rate_hz, "messages per second per channel and client, at most (decimation)")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 10000.0));
  cmd->add_option("--max-clients", a.max_clients, "WebSocket clients served at once")->capture_default_str()->check(CLI::Range(1, 64));
}

// The server, or nullptr after saying why.
std::unique_ptr<live::LiveServer> start_server(const ServeArgs& a, const char* cmd, const std::string& name,
                                               std::map<std::string, std::string> metadata) {
  live::LiveOptions o;
  try {
    live::parse_listen_address(a.listen, o);
    o.rate_hz = a.rate_hz;
    o.max_clients = a.max_clients;
    o.name = name;
    o.metadata = std::move(metadata);
    auto server = std::make_unique<live::LiveServer>(o);
    std::fprintf(stderr, "mechsim %s: serving ws://%s:%u (Foxglove WebSocket, foxglove.websocket.v1) and the page http://%s:%u/; "
                         "Ctrl-C stops\n", cmd, o.address.c_str(), server->port(), o.address.c_str(), server->port());
    return server;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim %s: %s\n", cmd, e.what());
    return nullptr;
  }
}

void print_stats(const char* cmd, const live::LiveServer& server) {
  const live::LiveStats s = server.stats();
  std::fprintf(stderr, "mechsim %s: %llu samples read, %llu messages sent to %llu clients (%llu dropped for not reading)\n", cmd,
               static_cast<unsigned long long>(s.samples_offered), static_cast<unsigned long long>(s.messages_sent),
               static_cast<unsigned long long>(s.clients_connected), static_cast<unsigned long long>(s.clients_dropped));
}

struct TopicServeArgs : ServeArgs {
  int domain = -1;
  std::vector<std::string> topics;
  std::string regex;
  std::string scene;
};

int serve_domain(const TopicServeArgs& a) {
  live::DomainSourceOptions d;
  d.domain = a.domain;
  d.topics.names = a.topics;
  d.topics.regex = a.regex;
  try {
    d.topics.validate();
    if (!a.scene.empty()) {  // an FMU participant's variable names, from the run's scene
      const config::Scene scene = config::load_scene(a.scene);  // the plan refers to it
      const cosim::ScenePlan plan = cosim::ScenePlan::build(scene);
      for (const auto& node : plan.nodes())
        if (node.type->publishes->layout == transport::TopicLayout::sequences)
          d.topic_fields[node.topic] = recorder::fields_text(recorder::layout_of(*node.type->publishes));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim topic serve: %s\n", e.what());
    return 2;
  }
  hostrun::configure_dds_environment();
  catch_stop_signals();
  auto server = start_server(a, "topic serve", "mechsim domain " + std::to_string(a.domain), {{"domain", std::to_string(a.domain)}});
  if (!server) return 2;
  try {
    live::DomainSource source(*server, d);
    while (!stop_requested()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim topic serve: %s\n", e.what());
    return 1;
  }
  print_stats("topic serve", *server);
  return 0;
}

struct BagServeArgs : ServeArgs {
  std::string file;
  double rate = 1.0;
  bool loop = false;
};

int serve_recording(const BagServeArgs& a) {
  catch_stop_signals();
  auto server = start_server(a, "bag serve", "mechsim recording " + a.file, {{"file", a.file}});
  if (!server) return 2;
  live::BagServeOptions o;
  o.file = a.file;
  o.rate = a.rate;
  o.loop = a.loop;
  o.stop = &stop_requested();
  try {
    const live::BagServeReport r = live::serve_bag(*server, o);
    std::fprintf(stderr, "mechsim bag serve: %zu channels, %llu messages played in %d passes%s\n", r.channels,
                 static_cast<unsigned long long>(r.served), r.loops, r.stopped ? "" : "; serving the last values until Ctrl-C");
    while (!stop_requested()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim bag serve: %s\n", e.what());
    return 1;
  }
  print_stats("bag serve", *server);
  return 0;
}

}  // namespace

void add_topic_serve_command(CLI::App* topic, int& exit_code) {
  auto* cmd = topic->add_subcommand("serve", "Serve the domain's topics live: Foxglove WebSocket protocol and a browser page "
                                             "(docs/live.md)");
  auto a = std::make_shared<TopicServeArgs>();
  add_serve_options(cmd, *a);
  cmd->add_option("--domain", a->domain, "DDS domain id of the run (the launcher prints it)")->required()->check(CLI::Range(0, 232));
  cmd->add_option("--topics", a->topics, "serve only these topics (default: every mechsim topic)")->delimiter(',');
  cmd->add_option("--regex", a->regex, "serve the topics whose whole name matches (ECMAScript)");
  cmd->add_option("--scene", a->scene, "the run's scene: an FMU participant's channel carries its variable names");
  cmd->callback([a, &exit_code] { exit_code = serve_domain(*a); });
}

void add_bag_serve_command(CLI::App* bag, int& exit_code) {
  auto* cmd = bag->add_subcommand("serve", "Serve a recording live, paced in simulation time: Foxglove WebSocket protocol and a "
                                           "browser page (docs/live.md)");
  auto a = std::make_shared<BagServeArgs>();
  cmd->add_option("file", a->file, "the recording (.mcap)")->required()->check(CLI::ExistingFile);
  add_serve_options(cmd, *a);
  cmd->add_option("--rate", a->rate, "x real time (simulation seconds per wall second)")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_flag("--loop", a->loop, "start over at the end");
  cmd->callback([a, &exit_code] { exit_code = serve_recording(*a); });
}

}  // namespace mechsim::tools

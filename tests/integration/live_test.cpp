// The live server on real runs (docs/live.md): `mechsim launch --live` watched through the
// Foxglove WebSocket protocol by a client on loopback (ws_test_client.h), its samples
// decoded and compared with the nodes' own output logs; a late client; a client that never
// reads; the run's outputs byte-identical with and without watchers; `mechsim bag serve`
// and `mechsim topic serve`. Each test holds a DDS domain of its own (--set dds.domain).
#include <signal.h>

#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <thread>

#include "cdr_decoder.h"
#include "idl_schema.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/scene_plan.h"
#include "npm_reader.h"
#include "mechsim/transport/domain_lock.h"
#include "run_fixture.h"
#include "ws_test_client.h"

namespace mechsim::testing {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

struct Received {
  std::uint32_t subscription;
  std::uint64_t t_ns;
  std::vector<std::byte> cdr;
};

// What a client saw: serverInfo, the channels advertised (by topic), the messages.
struct Watch {
  json server_info;
  std::map<std::string, json> channels;
  std::map<std::uint32_t, std::string> topic_of_subscription;
  std::vector<Received> messages;
  std::map<std::string, std::vector<std::chrono::steady_clock::time_point>> arrivals;  // by topic

  void take(WsTestClient& c) {
    for (auto& f : c.take()) {
      if (!f.binary) {
        const json j = json::parse(f.data);
        if (j["op"] == "serverInfo") server_info = j;
        if (j["op"] == "advertise")
          for (const auto& ch : j["channels"]) channels[ch["topic"]] = ch;
        continue;
      }
      Received r{};
      ASSERT_GE(f.data.size(), 13u);
      ASSERT_EQ(static_cast<unsigned char>(f.data[0]), 0x01);
      std::memcpy(&r.subscription, f.data.data() + 1, 4);
      std::memcpy(&r.t_ns, f.data.data() + 5, 8);
      r.cdr.resize(f.data.size() - 13);
      std::memcpy(r.cdr.data(), f.data.data() + 13, r.cdr.size());
      arrivals[topic_of_subscription[r.subscription]].push_back(f.received);
      messages.push_back(std::move(r));
    }
  }
  // Subscribes to every channel advertised so far that is not subscribed yet.
  void subscribe_all(WsTestClient& c) {
    json subs = json::array();
    for (const auto& [topic, ch] : channels) {
      bool known = false;
      for (const auto& [id, t] : topic_of_subscription) known = known || t == topic;
      if (known) continue;
      const std::uint32_t id = static_cast<std::uint32_t>(topic_of_subscription.size() + 1);
      topic_of_subscription[id] = topic;
      subs.push_back({{"id", id}, {"channelId", ch["id"]}});
    }
    if (!subs.empty()) c.send_text(json{{"op", "subscribe"}, {"subscriptions", subs}}.dump());
  }
  std::vector<const Received*> of(const std::string& topic) const {
    std::vector<const Received*> out;
    for (const auto& m : messages)
      if (topic_of_subscription.at(m.subscription) == topic) out.push_back(&m);
    return out;
  }
};

// The port a server printed ("ws://127.0.0.1:PORT"), 0 until it did.
int printed_port(const std::string& log) {
  std::smatch m;
  const std::string text = slurp(log);
  return std::regex_search(text, m, std::regex("ws://127\\.0\\.0\\.1:([0-9]+)")) ? std::stoi(m[1]) : 0;
}
int wait_for_port(const std::string& log, pid_t pid) {
  for (int i = 0; i < 3000; ++i) {
    if (const int port = printed_port(log)) return port;
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return 0;
    std::this_thread::sleep_for(10ms);
  }
  return 0;
}

class Live : public RunFolderTest {
 protected:
  std::vector<std::string> run_args(const std::string& tag, std::vector<std::string> extra) const {
    // Real-time at 1x: the run lasts its 2 simulated seconds, long enough to watch.
    extra.insert(extra.end(), {"--mode", "realtime", "--rtf", "1", "--set", "dds.domain=" + std::to_string(domain_.domain_id())});
    return launch_args(scene_path("cam_press.yaml"), tag, extra);
  }
  transport::DomainLock domain_ = transport::DomainLock::acquire();
};

// The decoded sample's field `name` (a double).
double field(const recorder::MessageLayout& layout, const recorder::DecodedSample& s, const std::string& name) {
  const int i = layout.field_index(name);
  EXPECT_GE(i, 0) << name;
  return i < 0 ? NAN : recorder::as_number(s.values[static_cast<std::size_t>(i)]);
}

TEST_F(Live, ARunWatchedThroughTheProtocolShowsTheNodesValuesAndIsUnchanged) {
  const double rate = 30;
  const pid_t pid = spawn(run_args("live", {"--live", "0", "--live-rate", "30"}), log("live"));
  const int port = wait_for_port(log("live"), pid);
  ASSERT_GT(port, 0) << slurp(log("live"));
  const std::string uri = "ws://127.0.0.1:" + std::to_string(port) + "/";
  WsTestClient client(uri, "foxglove.websocket.v1", 5s);
  ASSERT_TRUE(client.opened());
  EXPECT_EQ(client.subprotocol(), "foxglove.websocket.v1");
  Watch w, late_watch;
  std::unique_ptr<WsTestClient> late;
  const auto connected = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point late_subscribed;
  std::size_t late_subscriptions = 0;
  while (!RunFolderTest::has_exited(pid)) {
    w.take(client);
    w.subscribe_all(client);
    // A client that comes half-way through: every channel, and each one's latest value at once.
    if (!late && std::chrono::steady_clock::now() - connected > 1500ms) {
      late = std::make_unique<WsTestClient>(uri, "foxglove.websocket.v1", 5s);
      EXPECT_TRUE(late->opened());
      // Its advertisement first (the run's four topics at least), however long that takes here.
      for (const auto until = std::chrono::steady_clock::now() + 5s;
           late_watch.channels.size() < 4 && std::chrono::steady_clock::now() < until;) {
        late_watch.take(*late);
        std::this_thread::sleep_for(5ms);
      }
      late_watch.subscribe_all(*late);
      late_subscriptions = late_watch.topic_of_subscription.size();
      late_subscribed = std::chrono::steady_clock::now();
    }
    if (late) late_watch.take(*late);
    std::this_thread::sleep_for(5ms);
  }
  const auto ended = std::chrono::steady_clock::now();
  const CommandResult r = wait_for(pid, log("live"), 60);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  w.take(client);
  const json s = summary("live");

  // serverInfo names the run; one channel per topic of the run, with the recordings' schema.
  EXPECT_EQ(w.server_info["metadata"]["run_id"], s["run_id"]);
  EXPECT_EQ(w.server_info["metadata"]["scene"], "cam_press");
  for (const auto& [topic, type] : std::map<std::string, std::string>{{"cam/state", "mechsim::msg::CamState"},
                                                                      {"follower/state", "mechsim::msg::FollowerState"},
                                                                      {"mechsim/control", "mechsim::msg::Control"},
                                                                      {"mechsim/status", "mechsim::msg::Status"}}) {
    ASSERT_TRUE(w.channels.count(topic)) << topic;
    const json& ch = w.channels[topic];
    EXPECT_EQ(ch["schemaName"], type);
    EXPECT_EQ(ch["encoding"], "cdr");
    EXPECT_EQ(ch["schemaEncoding"], "omgidl");
    EXPECT_EQ(ch["schema"], recorder::schema_text(*recorder::find_layout(type))) << topic;
    EXPECT_TRUE(late_watch.channels.count(topic)) << "the late client lacks " << topic;
  }

  // The values are the nodes' own, at the same steps (their output logs: one row a step).
  const std::uint64_t run_id = std::stoull(s["run_id"].get<std::string>(), nullptr, 16);
  for (const auto& [topic, node] : std::map<std::string, std::string>{{"cam/state", "cam"}, {"follower/state", "follower"}}) {
    SCOPED_TRACE(topic);
    const recorder::MessageLayout& layout = *recorder::find_layout(w.channels[topic]["schemaName"].get<std::string>());
    const cosim::OutputLog out = cosim::read_output_log((run_folder("live") / (node + ".outputs.bin")).string());
    const auto messages = w.of(topic);
    // 2 s at 30 Hz: about 60; a loaded machine misses ticks, not most.
    EXPECT_GE(messages.size(), 20u);
    std::set<std::uint64_t> steps;
    for (const Received* m : messages) {
      const recorder::DecodedSample d = recorder::decode_sample(m->cdr, layout);
      EXPECT_EQ(d.header.run_id, run_id);
      EXPECT_EQ(m->t_ns, static_cast<std::uint64_t>(std::llround(d.header.t * 1e9)));  // simulation time
      ASSERT_LT(d.header.step, out.rows());
      steps.insert(d.header.step);
      for (std::size_t f = 0; f < layout.fields.size(); ++f) {
        const int col = out.column(layout.fields[f].name);
        if (col >= 0) {
          EXPECT_EQ(recorder::as_number(d.values[f]), out.data[col][d.header.step]) << layout.fields[f].name;
        }
      }
    }
    EXPECT_EQ(steps.size(), messages.size()) << "a step sent twice";
    // At most `rate` messages a second: one per tick of 1/rate s while the client was there.
    const double watched = std::chrono::duration<double>(ended - connected).count();
    EXPECT_LE(static_cast<double>(messages.size()), rate * watched + 1) << messages.size() << " in " << watched << " s";
  }
  // The late client had each data channel's latest value within a tick or two of subscribing.
  ASSERT_TRUE(late);
  EXPECT_GE(late_subscriptions, 4u);
  for (const std::string topic : {"cam/state", "follower/state", "mechsim/control"}) {
    ASSERT_FALSE(late_watch.arrivals[topic].empty()) << topic;
    EXPECT_LT(std::chrono::duration<double>(late_watch.arrivals[topic].front() - late_subscribed).count(), 0.5) << topic;
  }
  EXPECT_EQ(s["live"]["clients"], 2);
  EXPECT_EQ(s["live"]["clients_dropped"], 0);

  // The run does not notice: the same outputs without a live server.
  const CommandResult plain = run(run_args("plain", {}), log("plain"), 120);
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  expect_identical_node_outputs(run_folder("live"), run_folder("plain"), s, "runs with and without a watched live server");
}

TEST_F(Live, AClientThatNeverReadsDoesNotHoldTheRun) {
  // As many messages as the run has samples (rate 10000 > 1000 steps/s): the most a server
  // can queue for a client that stopped reading.
  const pid_t pid = spawn(run_args("live", {"--live", "0", "--live-rate", "10000"}), log("live"));
  const int port = wait_for_port(log("live"), pid);
  ASSERT_GT(port, 0) << slurp(log("live"));
  WsTestClient client("ws://127.0.0.1:" + std::to_string(port) + "/", "foxglove.websocket.v1", 5s);
  ASSERT_TRUE(client.opened());
  Watch w;
  for (int i = 0; i < 100 && w.channels.size() < 4; ++i) {
    w.take(client);
    std::this_thread::sleep_for(10ms);
  }
  w.subscribe_all(client);
  std::this_thread::sleep_for(20ms);
  client.stop_reading();
  const CommandResult r = wait_for(pid, log("live"), 60);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json s = summary("live");
  // Real time at 1x: 2 simulated seconds in about 2 wall seconds, as without a client.
  EXPECT_LT(s["wall_time_s"].get<double>(), 2.5) << s.dump(2);
  const CommandResult plain = run(run_args("plain", {}), log("plain"), 120);
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  expect_identical_node_outputs(run_folder("live"), run_folder("plain"), s, "runs with and without a client that never reads");
}

// A recording served paced: the same samples, at their simulation times, at about 1x.
TEST_F(Live, BagServePlaysARecordingPacedInSimulationTime) {
  const CommandResult rec = run(launch_args(scene_path("cam_press.yaml"), "rec",
                                            {"--set", "record=true", "--set", "dds.domain=" + std::to_string(domain_.domain_id())}),
                                log("rec"), 120);
  ASSERT_EQ(rec.exit_code, 0) << rec.output;
  const std::string file = (run_folder("rec") / "recording.mcap").string();
  const pid_t pid = spawn({kMechsim, "bag", "serve", file, "0", "--rate", "1", "--live-rate", "20"}, log("serve"));
  const int port = wait_for_port(log("serve"), pid);
  ASSERT_GT(port, 0) << slurp(log("serve"));
  WsTestClient client("ws://127.0.0.1:" + std::to_string(port) + "/", "foxglove.websocket.v1", 5s);
  ASSERT_TRUE(client.opened());
  Watch w;
  const auto start = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - start < 3s && slurp(log("serve")).find("passes") == std::string::npos) {
    w.take(client);
    w.subscribe_all(client);
    std::this_thread::sleep_for(5ms);
  }
  w.take(client);
  ::kill(pid, SIGINT);
  const CommandResult r = wait_for(pid, log("serve"), 30);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(w.channels.count("cam/state")) << r.output;
  const auto cam = w.of("cam/state");
  ASSERT_GE(cam.size(), 10u);
  const recorder::MessageLayout& layout = *recorder::find_layout("CamState");
  const cosim::OutputLog out = cosim::read_output_log((run_folder("rec") / "cam.outputs.bin").string());
  for (const Received* m : cam) {
    const recorder::DecodedSample d = recorder::decode_sample(m->cdr, layout);
    ASSERT_LT(d.header.step, out.rows());
    EXPECT_EQ(field(layout, d, "angle"), out.data[out.column("angle")][d.header.step]);
  }
  // Paced: the simulated time of the samples follows the wall clock of their arrival at
  // 1x (2 s of recording over about 2 s), not all at once.
  const auto& arrivals = w.arrivals["cam/state"];
  const double wall = std::chrono::duration<double>(arrivals.back() - arrivals.front()).count();
  const double simulated = (cam.back()->t_ns - cam.front()->t_ns) * 1e-9;
  EXPECT_NEAR(wall, simulated, 0.3) << "wall " << wall << " s, simulated " << simulated << " s";
}

// `mechsim topic serve` on a domain with a run on it: its topics appear by discovery.
TEST_F(Live, TopicServeFollowsARunningDomain) {
  const pid_t serve = spawn({kMechsim, "topic", "serve", "0", "--domain", std::to_string(domain_.domain_id())}, log("serve"));
  const int port = wait_for_port(log("serve"), serve);
  ASSERT_GT(port, 0) << slurp(log("serve"));
  WsTestClient client("ws://127.0.0.1:" + std::to_string(port) + "/", "foxglove.websocket.v1", 5s);
  ASSERT_TRUE(client.opened());
  const pid_t run_pid = spawn(run_args("run", {}), log("run"));
  Watch w;
  while (!RunFolderTest::has_exited(run_pid)) {
    w.take(client);
    w.subscribe_all(client);
    std::this_thread::sleep_for(5ms);
  }
  const CommandResult r = wait_for(run_pid, log("run"), 60);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  std::this_thread::sleep_for(100ms);
  w.take(client);
  ::kill(serve, SIGINT);
  const CommandResult sr = wait_for(serve, log("serve"), 30);
  EXPECT_EQ(sr.exit_code, 0) << sr.output;
  EXPECT_EQ(w.server_info["metadata"]["domain"], std::to_string(domain_.domain_id()));
  for (const std::string topic : {"cam/state", "follower/state"}) {
    ASSERT_TRUE(w.channels.count(topic)) << topic;
    EXPECT_GE(w.of(topic).size(), 10u) << topic;
  }
}

// The protocol's own client (@foxglove/ws-protocol) and Foxglove's OMG IDL deserializer
// (@foxglove/omgidl-serialization) watch a run; the browser page's decoder (live.js) decodes
// the same messages. Both give the nodes' logged values at the logged steps.
struct ReferenceRun {
  std::string scene;
  std::vector<std::string> args;
};
void PrintTo(const ReferenceRun& r, std::ostream* os) { *os << r.scene; }
class LiveReference : public Live, public ::testing::WithParamInterface<ReferenceRun> {};

TEST_P(LiveReference, TheProtocolsOwnClientAndThePageDecodeTheNodesValues) {
  if (!npm_reader::in_path("node")) GTEST_SKIP() << "node not installed (Debian packages nodejs, npm)";
  const std::filesystem::path client_dir = std::filesystem::path(MECHSIM_BIN_DIR).parent_path() / "live-client";
  if (!std::filesystem::exists(client_dir / "node_modules" / "@foxglove" / "ws-protocol") ||
      npm_reader::read_text(client_dir / ".installed-package-lock.json") !=
          npm_reader::read_text(std::string(MECHSIM_SOURCE_DIR) + "/tests/integration/live_client/package-lock.json"))
    GTEST_SKIP() << "@foxglove/ws-protocol is not installed (from the current lock file) in " << client_dir
                 << ": run tools/install-test-deps.sh (it needs the npm registry once)";
  const ReferenceRun& p = GetParam();
  std::vector<std::string> args = p.args;
  args.insert(args.end(), {"--live", "0", "--set", "dds.domain=" + std::to_string(domain_.domain_id())});
  const pid_t pid = spawn(launch_args(scene_path(p.scene), "run", args), log("run"));
  const int port = wait_for_port(log("run"), pid);
  ASSERT_GT(port, 0) << slurp(log("run"));
  const std::string out = (dir_ / "watched.json").string();
  const pid_t watcher = spawn({"/usr/bin/env", "node", (client_dir / "watch_live.mjs").string(), "ws://127.0.0.1:" + std::to_string(port) + "/",
                               std::string(MECHSIM_SOURCE_DIR) + "/tools/live/page/live.js", out, "120"},
                              log("watcher"));
  const CommandResult r = wait_for(pid, log("run"), 120);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const CommandResult w = wait_for(watcher, log("watcher"), 30);  // ends when the server closes
  ASSERT_EQ(w.exit_code, 0) << w.output;
  const json seen = json::parse(slurp(out));
  ASSERT_TRUE(seen["errors"].empty()) << seen["errors"].dump(2);
  EXPECT_EQ(seen["serverInfo"]["metadata"]["run_id"], summary("run")["run_id"]);
  const config::Scene scene = config::load_scene(scene_path(p.scene));  // the plan refers to it
  const cosim::ScenePlan plan = cosim::ScenePlan::build(scene);
  for (const auto& node : plan.nodes()) {
    SCOPED_TRACE(node.topic);
    const cosim::OutputLog log_of_node = cosim::read_output_log((run_folder("run") / (node.name() + ".outputs.bin")).string());
    // An FMU participant's channel names its sequences' elements ("mechsim.fields"): the
    // page shows "y" where Foxglove shows "reals[0]".
    std::map<std::string, std::string> foxglove_name;  // page name -> Foxglove's
    for (const auto& ch : seen["channels"])
      if (ch["topic"] == node.topic && ch.contains("mechsim.fields")) {
        const recorder::MessageLayout named = recorder::fmu_layout_from_text(ch["mechsim.fields"].get<std::string>());
        std::map<recorder::CdrKind, int> index;
        const std::map<recorder::CdrKind, std::string> sequence{
            {recorder::CdrKind::f64, "reals"}, {recorder::CdrKind::i32, "integers"}, {recorder::CdrKind::boolean, "booleans"}};
        for (const auto& f : named.fields) foxglove_name[f.name] = sequence.at(f.kind) + "[" + std::to_string(index[f.kind]++) + "]";
      }
    int messages = 0, compared = 0;
    for (const auto& m : seen["messages"]) {
      if (m["topic"] != node.topic) continue;
      ++messages;
      const json& fox = m["foxglove"];
      const auto step = fox["header.step"].get<std::uint64_t>();
      ASSERT_LT(step, log_of_node.rows());
      EXPECT_EQ(m["timestamp_ns"].get<double>(), std::round(fox["header.t"].get<double>() * 1e9));
      for (const auto& [key, value] : m["page"].items()) {
        const std::string fox_key = foxglove_name.count(key) ? foxglove_name[key] : key;
        ASSERT_TRUE(fox.contains(fox_key)) << fox_key;
        // The page plots booleans as 0 and 1.
        const json expected = fox[fox_key].is_boolean() ? json(fox[fox_key].get<bool>() ? 1 : 0) : fox[fox_key];
        EXPECT_EQ(value, expected) << key << ": the page's decoder and Foxglove's differ";
        const int col = log_of_node.column(key);
        if (col < 0 || !value.is_number()) continue;
        ++compared;
        EXPECT_EQ(value.get<double>(), log_of_node.data[col][step]) << key << " at step " << step;
      }
    }
    EXPECT_GE(messages, 10);
    EXPECT_GE(compared, messages);  // at least one logged field a message
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, LiveReference,
                         ::testing::Values(ReferenceRun{"cam_press.yaml", {"--mode", "realtime", "--rtf", "1"}},
                                           ReferenceRun{"nc_slide_loop.yaml", {"--end", "1 s"}},
                                           // FMU participants: their variable names. 3 s: Node.js
                                           // starting beside a busy suite took over a second.
                                           ReferenceRun{"fmu_speed_lag.yaml", {"--mode", "realtime", "--rtf", "1", "--end", "3 s"}}),
                         [](const auto& info) { return info.param.scene.substr(0, info.param.scene.find('.')); });

}  // namespace
}  // namespace mechsim::testing

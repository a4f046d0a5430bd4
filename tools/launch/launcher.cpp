#include "launcher.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string_view>

#include "agent_client.h"
#include "agent_protocol.h"
#include "mechsim/transport/domain_lock.h"
#include "domain_readers.h"
#include "hosts.h"
#include "mechsim/config/scene.h"
#include "fmu_probe.h"
#include "mechsim/cosim/fmu_probe.h"
#include "mechsim/cosim/fmu_unpacking.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/transport/backends.h"
#include "mechsim/transport/network_config.h"
#include "replay_input.h"
#include "run_recording.h"
#include "live_run.h"
#include "run_security.h"
#include "install_paths.h"
#include "divergence_advice.h"
#include "run_comparison.h"
#include "run_summary.h"
#include "agent_host.h"
#include "process_host.h"
#include "process_packing.h"
#include "mechsim/cosim/supervisor.h"
#include "json_io.h"
#include "provenance.h"
#include "realtime_report.h"
#include "elapsed.h"

namespace mechsim::launch {

// Node processes, agents, hosts and install paths: the layer below launch (tools/hostrun).
using namespace hostrun;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using nlohmann::json;

namespace {

std::atomic<int> g_interrupt{0};
void on_interrupt(int sig) { g_interrupt.store(sig); }

// The DDS lease of a multi-host run: a cut shorter than the partition grace must not make
// the participants forget each other (what was written meanwhile would be lost for good).
double lease_for(const config::Scene& scene) { return config::fault_timings(scene).dds_lease; }

class Run {
 public:
  Run(const LaunchOptions& o, config::Scene& scene, cosim::ScenePlan& plan, HostLayout hosts)
      : opt_(o), scene_(scene), plan_(plan), hosts_(std::move(hosts)) {}
  // The FMUs the run's processes unpacked, however those processes ended (fmu_unpacking.h).
  ~Run() {
    if (run_dir_.empty()) return;
    if (const std::string why = cosim::remove_fmu_unpack_folder(run_dir_); !why.empty())
      std::fprintf(stderr, "mechsim: warning: %s\n", why.c_str());
  }

  int execute();

 private:
  void open_run_folder();
  int connect();
  void place_nodes();
  cosim::SupervisedRun run_nodes();
  int report(cosim::SupervisedRun out);
  std::string log_of(const std::string& node) const;
  void print_progress(const cosim::NodeWatches& watches, double since_start, bool final_line);

  const LaunchOptions& opt_;
  config::Scene& scene_;
  cosim::ScenePlan& plan_;
  std::uint64_t run_id_ = 0;
  std::string run_dir_;
  int domain_ = 0;
  std::optional<transport::DomainLock> domain_lock_;  // held until the run ends (a domain the scene does not fix)
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<transport::ControlWriter> control_;
  std::unique_ptr<transport::StatusReader> status_;
  HostLayout hosts_;
  std::unique_ptr<AgentClient> agents_;  // multi-host runs; outlives remote_, which uses it
  std::vector<std::string> hand_back_problems_;
  std::unique_ptr<ProcessNodeHost> local_;   // the node processes on this machine
  std::unique_ptr<AgentNodeHost> remote_;    // those the agents start on other hosts
  std::unique_ptr<cosim::Supervisor> supervisor_;
  bool tty_ = false;
  std::map<std::string, std::string> replay_tables_;  // node -> table its process replays
  std::unique_ptr<RunRecording> recording_;
  std::unique_ptr<DomainReaders> domain_readers_;  // who reads the nodes' topics (a user's recorder)
  std::unique_ptr<live::LiveRun> live_;            // --live: the run's live server, never waited for
};

// The last line of a node's log that says "error" (for a node that died before its status
// carried the message).
std::string last_error_line(const std::string& log_path) {
  std::ifstream in(log_path);
  std::string line, last;
  while (std::getline(in, line))
    if (line.find("error") != std::string::npos) last = line;
  return last;
}

void Run::print_progress(const cosim::NodeWatches& watches, double since_start, bool final_line) {
  if (!tty_ || !opt_.progress) return;
  std::uint64_t step = UINT64_MAX;
  for (const auto& [name, w] : watches) step = std::min<std::uint64_t>(step, w.seen ? w.last.header.step : 0);
  double t = scene_.time.end;  // an adaptive run's grid grows in the nodes, not here: their heartbeats' t
  for (const auto& [name, w] : watches) t = std::min(t, w.seen ? w.last.header.t : scene_.time.start);
  if (!plan_.grid()->is_adaptive()) t = plan_.grid()->time(std::min(step, plan_.grid()->steps()));
  const double rate = since_start > 0 ? static_cast<double>(step) / since_start : 0.0;
  const double rtf = since_start > 0 ? (t - scene_.time.start) / since_start : 0.0;
  std::string realtime;
  if (scene_.mode == config::RunMode::realtime) {
    long long missed = 0;
    double late = 0, p99 = 0;
    for (const auto& [name, w] : watches) {
      missed += w.last.missed_deadlines;
      late = std::max(late, w.last.lateness_max);
      p99 = std::max(p99, w.last.lateness_p99);
    }
    char buf[128];
    std::snprintf(buf, sizeof buf, "  missed %lld  late p99 %.3f ms  max %.2f ms", missed, p99 * 1e3, late * 1e3);
    realtime = buf;
  }
  const std::string of_steps = plan_.grid()->is_adaptive() ? "" : " / " + std::to_string(plan_.grid()->steps());
  std::fprintf(stderr, "\r[%s] t = %.4f / %.4f s  step %llu%s  %.0f steps/s  rtf %.2f%s   %s", scene_.name.c_str(), t,
               scene_.time.end, static_cast<unsigned long long>(step), of_steps.c_str(), rate, rtf, realtime.c_str(),
               final_line ? "\n" : "");
  std::fflush(stderr);
}

// Where each node runs (cosim/node_host.h): a process of its own or of its group on this
// machine, or a process an agent starts on another host.
void Run::place_nodes() {
  std::string scene_text;
  if (agents_) {
    std::ifstream in(run_dir_ + "/scene.yaml");
    scene_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::vector<LocalProcess> local;
  std::vector<RemoteNode> remote;
  std::map<std::string, std::size_t> group_index;  // group -> its entry in `local`
  std::map<std::string, std::size_t> remote_group_index;  // group -> its entry in `remote`
  for (const auto& node : plan_.nodes()) {
    const std::string& group = scene_.find_participant(node.name())->process;
    if (auto at = hosts_.remote.find(node.name()); at != hosts_.remote.end()) {
      // Its host's agent starts it (the request: below); a group's members in one process
      // there (all on the same host: config checks).
      if (!group.empty() && remote_group_index.count(group)) {
        remote[remote_group_index[group]].members.push_back(node.name());
        continue;
      }
      if (!group.empty()) remote_group_index[group] = remote.size();
      remote.push_back({group.empty() ? node.name() : "process-" + group, {node.name()}, scene_.find_participant(node.name())->host,
                        at->second, group.empty() ? node.type->name : std::string(hostrun::kGroupType), ""});
      continue;
    }
    if (!group.empty() && group_index.count(group)) {
      // Another thread of the group's process (docs/scenes.md, `process`).
      LocalProcess& p = local[group_index[group]];
      p.members.push_back(node.name());
      p.command_line.nodes.push_back(node.name());
      if (auto it = replay_tables_.find(node.name()); it != replay_tables_.end())
        p.command_line.replays.push_back(node.name() + "=" + it->second);
      continue;
    }
    LocalProcess p;
    p.name = group.empty() ? node.name() : group;
    p.members = {node.name()};
    p.executable = node_executable(group.empty() ? node.type->name : hostrun::kGroupType);
    p.command_line = {.scene = run_dir_ + "/scene.yaml", .nodes = {node.name()}, .run_id = run_id_, .domain = domain_,
                      .run_dir = run_dir_};
    // The node takes commands from this launcher's control writer only (docs/faults.md).
    p.command_line.control_writer = control_->guid();
    if (auto it = replay_tables_.find(node.name()); it != replay_tables_.end())
      p.command_line.replays.push_back(group.empty() ? it->second : node.name() + "=" + it->second);
    p.log_path = run_dir_ + "/" + (group.empty() ? node.name() : "process-" + group) + ".log";
    p.environment = node_security_environment(scene_, node.name());
    if (!group.empty()) group_index[group] = local.size();
    local.push_back(std::move(p));
  }
  // The agents' start requests: the same arguments as a local node's, in a run folder of
  // the agent's own (agent_protocol.h).
  for (RemoteNode& r : remote) {
    json request{{"type", r.type}, {"scene_yaml", scene_text}, {"run_folder", fs::path(run_dir_).filename().string()},
                 {"domain", domain_}, {"address", r.address}, {"peers", hosts_.peers}, {"lease_s", lease_for(scene_)},
                 {"partition_grace_s", scene_.faults.partition_grace}, {"control_writer", control_->guid()},
                 {"participants_per_host", hosts_.participants_per_host}};
    if (r.type == hostrun::kGroupType) request["members"] = r.members;
    request["files"] = agents_->send_files(r.address, files_of(scene_, r.members));  // the FMUs travel with the run
    r.request = request.dump();
  }
  local_ = std::make_unique<ProcessNodeHost>(std::move(local));
  if (!remote.empty()) remote_ = std::make_unique<AgentNodeHost>(*agents_, std::move(remote));
}

std::string Run::log_of(const std::string& node) const {
  // An agent streams a remote node's log into <node>.log here.
  if (remote_ && !remote_->placement(node).empty()) return run_dir_ + "/" + remote_->log_name(node);
  return local_->log_of(node);
}

cosim::SupervisedRun Run::run_nodes() {
  place_nodes();
  cosim::SupervisorOptions o;
  o.run_id = run_id_;
  o.run_dir = run_dir_;
  o.ready_timeout_s = opt_.ready_timeout_s;
  o.hang_timeout_s = scene_.hang_timeout;
  o.fault_timings = config::fault_timings(scene_);
  o.restart_limit = static_cast<int>(scene_.faults.restart_limit);
  o.checkpoint_every = scene_.faults.checkpoint_every;
  for (const auto& p : scene_.participants)
    if (p.restart) o.restartable.push_back(p.name);
  const bool realtime = scene_.mode == config::RunMode::realtime;
  o.start = transport::ControlMessage{run_id_, transport::ControlCommand::start, scene_.time.end, scene_.time.step,
                                      realtime ? transport::RunMode::realtime : transport::RunMode::lockstep, scene_.rtf, 0, 0, 0, {}};
  o.not_ready_hint = " (see their logs in " + run_dir_ + ")";
  if (!plan_.grid()->is_adaptive()) o.last_step = plan_.grid()->steps();

  cosim::SupervisorHooks hooks;
  hooks.interrupted = [] { return g_interrupt.load(); };
  hooks.say = [this](const std::string& line) {
    if (tty_ && opt_.progress) std::fprintf(stderr, "\n");
    std::fprintf(stderr, "mechsim: %s\n", line.c_str());
  };
  hooks.exit_message = [this](const std::string& node, std::string message) {
    const std::string log = log_of(node);
    if (message.empty()) message = last_error_line(log);
    // The status carries at most 256 characters: the node's log has the whole message.
    if (message.size() >= 250) {
      const std::string line = last_error_line(log);
      if (const auto at = line.find(message.substr(0, 40)); at != std::string::npos) message = line.substr(at);
    }
    return message;
  };
  if (recording_)
    hooks.recorder_matched = [this]() -> std::string {
      return recording_->wait_matched(std::chrono::seconds(10)) ? "" : "the recorder's readers did not match the nodes' writers within 10 s";
    };
  // Every reader on the domain (a recorder the user started first) matched by the writer
  // it reads: each node reports how many it has matched (docs/recording.md).
  hooks.unmatched_readers = [this](const cosim::NodeWatches& watches) {
    std::string late;
    const auto domain_readers = domain_readers_ ? domain_readers_->by_topic_and_type() : decltype(domain_readers_->by_topic_and_type()){};
    for (const auto& node : plan_.nodes()) {
      const auto found = domain_readers.find({node.topic, node.type->publishes->idl_name});
      int readers = found == domain_readers.end() ? 0 : found->second;
      // The live server reads as a tool the run does not wait for (docs/live.md).
      if (live_) readers -= live_->readers()[{node.topic, node.type->publishes->idl_name}];
      const transport::StatusMessage& s = watches.at(node.name()).last;
      if (s.readers_matched < readers)
        late += (late.empty() ? "" : ", ") + node.name() + " (" + std::to_string(s.readers_matched) + " of " + std::to_string(readers) + ")";
    }
    return late;
  };
  hooks.progress = [this](const cosim::NodeWatches& watches, double since_start, bool final_line) {
    print_progress(watches, since_start, final_line);
  };
  std::vector<cosim::NodeHost*> hosts{local_.get()};
  if (remote_) hosts.push_back(remote_.get());
  supervisor_ = std::make_unique<cosim::Supervisor>(*participant_, *control_, *status_, hosts, o, hooks);
  cosim::SupervisedRun out = supervisor_->run();
  if (!out.ok && tty_ && opt_.progress) std::fprintf(stderr, "\n");
  return out;
}

int Run::execute() {
  tty_ = ::isatty(STDERR_FILENO);
  // Real-time process settings: refused here, before anything starts, when the nodes
  // (which inherit the launcher's credentials and limits) could not apply them.
  if (const auto problems = realtime_rights_problems(scene_); !problems.empty()) {
    for (const auto& why : problems) std::fprintf(stderr, "mechsim launch: %s: %s\n", scene_.file.c_str(), why.c_str());
    std::fprintf(stderr, "mechsim launch: refused: the scene asks for real-time settings this process may not apply "
                         "(docs/realtime.md, 'Rights'); nothing was started\n");
    return 2;
  }
  // DDS security (docs/security.md): every identity the run needs, before anything starts.
  if (const auto problems = security_problems(scene_); !problems.empty()) {
    for (const auto& why : problems) std::fprintf(stderr, "mechsim launch: %s\n", why.c_str());
    return 2;
  }
  open_run_folder();
  // Each FMU instantiated once in a child before the nodes start (fmu_probe.h), unpacked
  // where the nodes find it: a crash there is named, and takes only the child down.
  if (const std::string why = tools::probe_fmus_in_children(run_dir_ + "/scene.yaml", {}, plan_, cosim::fmu_unpack_folder(run_dir_));
      !why.empty()) {
    std::fprintf(stderr, "mechsim launch: %s\n", why.c_str());
    tools::write_json_file(run_dir_ + "/summary.json",
                           json{{"schema_version", tools::schema_version}, {"scene", scene_.name}, {"run_id", hex_id(run_id_)},
                                {"run_dir", run_dir_}, {"status", "failed"}, {"complete", false},
                                {"failure", {{"node", ""}, {"last_step", 0}, {"reason", why}}}});
    return 2;
  }
  if (const int refused = connect(); refused != 0) return refused;
  std::fprintf(stderr, "mechsim: scene '%s', run %s, domain %d, %zu nodes, folder %s\n", scene_.name.c_str(),
               hex_id(run_id_).c_str(), domain_, plan_.nodes().size(), run_dir_.c_str());
  // Replayed participants: their recorded topic, checked and tabulated before any process
  // starts (a recording that does not fit the scene is refused like a bad scene).
  for (const std::string& text : opt_.replays) {
    const ReplayRequest r = parse_replay_request(text);
    const std::string table = run_dir_ + "/" + r.node + ".replay.bin";
    try {
      write_replay_table(r.file, plan_.node(r.node), *plan_.grid(), table);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim launch: --replay %s: %s\n", text.c_str(), e.what());
      return 2;
    }
    replay_tables_[r.node] = table;
  }
  if (!opt_.live.empty()) {
    live::LiveOptions o;
    live::parse_listen_address(opt_.live, o);
    o.rate_hz = opt_.live_rate_hz;
    live_ = std::make_unique<live::LiveRun>(plan_, live::RunIdentity{scene_.name, scene_.file, hex_id(run_id_), run_dir_, domain_}, o);
    std::fprintf(stderr, "mechsim: live: %s\n", live_->describe().c_str());
  }
  recording_ = RunRecording::start(plan_, domain_, run_dir_);
  return report(run_nodes());
}

// The run's id and folder, with the resolved scene and a summary marked incomplete.
void Run::open_run_folder() {
  std::random_device rd;
  run_id_ = (static_cast<std::uint64_t>(rd()) << 32) ^ rd() ^ static_cast<std::uint64_t>(::getpid());
  run_dir_ = (fs::path(opt_.runs_dir) / (scene_.name + "-" + hex_id(run_id_).substr(8))).string();
  fs::create_directories(run_dir_);
  cosim::unpack_fmus_in_run_folder(run_dir_);  // the reference's FMUs too
  {
    std::ofstream f(run_dir_ + "/scene.yaml");
    f << "# resolved scene of run " << hex_id(run_id_) << " (from " << scene_.file << ", overrides applied)\n"
      << config::scene_to_yaml(scene_) << "\n";
  }
  // Until the run ends this summary says so: a launcher that is killed leaves a run folder
  // whose summary is marked incomplete, next to everything the nodes wrote (docs/faults.md).
  tools::write_json_file(run_dir_ + "/summary.json",
                         json{{"schema_version", tools::schema_version}, {"scene", scene_.name}, {"scene_file", scene_.file},
                              {"run_id", hex_id(run_id_)}, {"run_dir", run_dir_}, {"status", "incomplete"},
                              {"reason", "the launcher has not finished this run: it is still running, or it was killed. The node "
                                         "logs and output logs hold what was written; `mechsim record --recover` completes a "
                                         "recording (docs/faults.md)"}});
}

// The domain, the DDS and security environment the nodes inherit, the launcher's own
// participant, and in a multi-host run the agents. Returns an exit code when the run
// cannot go on (0: connected).
int Run::connect() {
  if (scene_.domain_id) {
    domain_ = *scene_.domain_id;
  } else {
    domain_lock_.emplace(transport::DomainLock::acquire());
    domain_ = domain_lock_->domain_id();
  }
  if (hosts_.multi_host) {
    // The hosts' interfaces and unicast peers for both vendors, generated from the scene,
    // for the launcher, its recorder and the local nodes (the agents write their own).
    set_environment(write_unicast_dds_files(run_dir_ + "/dds", {hosts_.launcher_address, hosts_.peers, lease_for(scene_),
                                                                hosts_.participants_per_host}));
  } else {
    configure_dds_environment();
  }
  configure_security_environment(scene_);
  if (!scene_.security_dir.empty())
    std::fprintf(stderr, "mechsim: DDS security: %s (authentication, access control, %s; docs/security.md)\n",
                 scene_.security_dir.c_str(),
                 scene_.security_protection == transport::kProtectionSign ? "signed, not encrypted: protection sign" : "encryption");
  participant_ = transport::create_participant(scene_.vendor, domain_);
  // Discovers while the nodes start. Not in a secured run on Fast DDS: the discovery
  // participant is Cyclone's, and secured Cyclone and Fast DDS do not complete a handshake
  // (docs/security.md); its failing handshakes with every node only cost the run (a secured
  // Fast DDS run then missed its 30 s start now and then). A secured recorder has to be
  // started with the run there (`record:`), as on any vendor.
  if (scene_.security_dir.empty() || scene_.vendor == "cyclone") domain_readers_ = std::make_unique<DomainReaders>(domain_);
  control_ = participant_->create_control_writer();
  status_ = participant_->create_status_reader();
  if (hosts_.multi_host) {
    agents_ = std::make_unique<AgentClient>(open_agent_link(hosts_, *participant_, domain_, run_dir_), run_id_, run_dir_);
    std::vector<std::string> addresses;
    for (const auto& [node, address] : hosts_.remote)
      if (std::find(addresses.begin(), addresses.end(), address) == addresses.end()) addresses.push_back(address);
    std::fprintf(stderr, "mechsim: multi-host run: launcher on %s (%s), waiting for the agents on %s (%s)\n",
                 hosts_.launcher_host.c_str(), hosts_.launcher_address.c_str(), join(addresses, ", ").c_str(),
                 hosts_.over_ssh ? "over ssh" : "standing DDS agents");
    const auto missing = agents_->wait_for_agents(addresses, opt_.ready_timeout_s, [] { return g_interrupt.load() != 0; });
    if (!missing.empty()) {
      if (hosts_.over_ssh) {
        for (const auto& a : missing) {
          std::string why = agents_->problem(a);
          if (why.empty()) why = "no answer within " + std::to_string(static_cast<int>(opt_.ready_timeout_s)) + " s";
          std::fprintf(stderr, "mechsim launch: no mechsim agent answered over ssh from %s: %s (docs/hosts.md)\n", a.c_str(), why.c_str());
        }
      } else {
        std::fprintf(stderr, "mechsim launch: no mechsim agent answered from %s on domain %d within %g s: start "
                             "`mechsim agent --domain %d --address ADDRESS --peers %s` on each of those hosts (docs/hosts.md)\n",
                     join(missing, ", ").c_str(), domain_, opt_.ready_timeout_s, domain_, hosts_.launcher_address.c_str());
      }
      return 1;
    }
  }
  return 0;
}

// After the run: advice, the remote nodes' files, the summary, the comparison, the report.
int Run::report(cosim::SupervisedRun out) {
  // Advice for a diverged run: computed here, once the run is over (it may run a search).
  if (out.diverged) out.reason += divergence_advice(scene_, run_dir_ + "/scene.yaml", out.failed_node);
  if (agents_) {
    // The remote nodes' files into this run folder: the same files as a single-host run.
    hand_back_problems_ = agents_->collect(30.0);
    for (const auto& why : hand_back_problems_) std::fprintf(stderr, "mechsim: warning: %s\n", why.c_str());
    if (out.ok && !hand_back_problems_.empty()) {
      out.ok = false;
      out.reason = "the run folder is incomplete: " + hand_back_problems_.front();
    }
  }
  bool fastdds = scene_.vendor == "fastdds";
  for (const auto& p : scene_.participants) fastdds = fastdds || p.vendor == "fastdds";
  // A killed Fast DDS node leaves its shared-memory segments in /dev/shm.
  if (!out.ok && fastdds) transport::clean_up_after_killed_processes();
  json summary = summarise(RunFacts{scene_, plan_, run_id_, run_dir_, domain_, hosts_, agents_ ? &agents_->agents() : nullptr,
                                    hand_back_problems_, *supervisor_, [this](const std::string& node) { return log_of(node); }},
                           out);
  if (!replay_tables_.empty()) {
    json replayed = json::object();
    for (const std::string& text : opt_.replays) {
      const ReplayRequest r = parse_replay_request(text);
      replayed[r.node] = r.file;
    }
    summary["replayed"] = replayed;
  }
  if (recording_) {
    // Samples published per topic: one output-log row per published step.
    std::map<std::string, std::uint64_t> published;
    for (const auto& node : plan_.nodes()) {
      try {
        published[node.topic] = cosim::read_output_log(run_dir_ + "/" + node.name() + ".outputs.bin").rows();
      } catch (const std::exception&) {
        published[node.topic] = 0;  // the node died before its log had a header
      }
    }
    summary["recording"] = recording_->finish(published);
    const json& rec = summary["recording"];
    std::fprintf(stderr, "mechsim: recorded %s: %llu messages, %.1f kB%s\n", rec["file"].get<std::string>().c_str(),
                 static_cast<unsigned long long>(rec["messages"].get<std::uint64_t>()), rec["bytes"].get<double>() / 1e3,
                 rec["complete"].get<bool>() ? ", every published sample" : " — INCOMPLETE: see summary.json 'recording'");
  }

  if (live_) {
    const live::LiveStats s = live_->stats();
    summary["live"] = {{"clients", s.clients_connected}, {"clients_dropped", s.clients_dropped},
                       {"messages_sent", s.messages_sent}, {"samples_read", s.samples_offered}};
  }
  if (out.ok) write_comparison(scene_, assess::compare_with_reference(scene_, plan_, run_dir_), run_dir_, opt_.plots, summary);
  if (opt_.plots && summary.contains("realtime")) plot_lateness(scene_, run_dir_, summary);
  tools::write_json_file(run_dir_ + "/summary.json", summary);
  if (!opt_.json_path.empty()) tools::write_json_file(opt_.json_path, summary);

  return print_run_report(summary, scene_, run_id_, run_dir_, out);
}

}  // namespace

std::vector<std::string> dds_layout_overrides(const std::vector<std::string>& participants, const std::string& layout) {
  if (layout != "cyclone" && layout != "fastdds" && layout != "mixed")
    throw std::invalid_argument("DDS layout: expected cyclone, fastdds or mixed, got '" + layout + "'");
  const bool mixed = layout == "mixed";
  std::vector<std::string> out{"dds.vendor=" + (mixed ? std::string("cyclone") : layout)};
  for (std::size_t i = 0; i < participants.size(); ++i)
    out.push_back("participants." + participants[i] + ".dds=" + (mixed ? (i % 2 == 0 ? "fastdds" : "cyclone") : layout));
  return out;
}

// A setting the launcher decides (--dds, redundant samples across hosts), set on the loaded
// scene and written into its document, so that the resolved scene.yaml in the run folder
// carries it to every node: the scene file is read and checked once.
static void set_on_loaded_scene(config::Scene& scene, const std::string& override_text) {
  const std::string key = override_text.substr(0, override_text.find('='));
  const std::string value = override_text.substr(override_text.find('=') + 1);
  scene.root.set_override(key, value);
  if (key == "dds.vendor") {
    scene.vendor = value;
  } else if (constexpr std::string_view prefix = "participants.", suffix = ".process";
             key.starts_with(prefix) && key.ends_with(suffix)) {
    const std::string name = key.substr(prefix.size(), key.size() - prefix.size() - suffix.size());
    for (auto& p : scene.participants)
      if (p.name == name) p.process = value;
  } else if (key == "faults.redundant_samples" && value == "true") {
    scene.faults.redundant_samples = config::RedundantSamples::always;
  } else {
    bool set = false;
    for (auto& p : scene.participants)
      if (key == "participants." + p.name + ".dds") {
        p.vendor = value;
        set = true;
      }
    if (!set) throw std::logic_error("the launcher cannot set '" + key + "' on a loaded scene");
  }
}

int launch(const LaunchOptions& options) {
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  config::Scene scene;
  std::optional<cosim::ScenePlan> plan;
  HostLayout hosts;
  try {
    scene = config::load_scene(options.scene_path, options.overrides);
    if (!options.dds_layout.empty()) {
      std::vector<std::string> names;
      for (const auto& p : scene.participants) names.push_back(p.name);
      for (const auto& o : dds_layout_overrides(names, options.dds_layout)) set_on_loaded_scene(scene, o);
    }
    // `processes: per_core | N`: this host's participants packed into process groups.
    for (const auto& [participant, group] : pack_processes(scene, usable_cores()))
      set_on_loaded_scene(scene, "participants." + participant + ".process=" + group);
    hosts = plan_hosts(scene);
    // Across a network packets get lost: every sample goes twice (docs/faults.md).
    if (hosts.multi_host && scene.faults.redundant_samples == config::RedundantSamples::automatic)
      set_on_loaded_scene(scene, "faults.redundant_samples=true");
    cosim::defer_fmu_instantiation();  // an FMU's code runs in the nodes and in the probes' children
    plan.emplace(cosim::ScenePlan::build(scene));
    auto vendors = transport::available_vendors();
    for (const auto& p : scene.participants)
      if (std::find(vendors.begin(), vendors.end(), p.vendor) == vendors.end())
        throw config::ConfigError(scene.file, p.key_path + ".dds",
                                  "expected a DDS vendor compiled into this build, got '" + p.vendor + "'");
  } catch (const config::ConfigError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  for (const std::string& text : options.replays) {
    try {
      const ReplayRequest r = parse_replay_request(text);
      if (!scene.find_participant(r.node))
        throw std::invalid_argument("--replay: no participant '" + r.node + "' in " + scene.file);
      // A recording holds the topic only: a compared output the topic lacks cannot be replayed.
      const cosim::PlannedNode& node = plan->node(r.node);
      std::vector<const config::SignalRef*> refs;
      for (const auto& c : scene.compare) refs.push_back(&c);
      for (const auto& rep : scene.report) {
        refs.push_back(&rep.signal);
        if (rep.at) refs.push_back(&*rep.at);
      }
      for (const config::SignalRef* ref : refs) {
        if (ref->participant != r.node) continue;
        const int out = node.block->output_index(ref->output);
        if (std::find(node.published_outputs.begin(), node.published_outputs.end(), out) == node.published_outputs.end())
          throw std::invalid_argument("--replay " + r.node + ": " + ref->key_path + " uses '" + ref->full_name() + "', which is not on topic '" +
                                      node.topic + "', so a recording cannot give it (remove it with --set or replay another participant)");
      }
    } catch (const std::invalid_argument& e) {
      std::fprintf(stderr, "mechsim launch: %s\n", e.what());
      return 2;
    }
  }
  if (scene.record) {
    auto vendors = transport::available_vendors();
    if (std::find(vendors.begin(), vendors.end(), "cyclone") == vendors.end()) {
      std::fprintf(stderr, "%s\n", config::ConfigError(scene.file, "record", "no 'record' section: recording needs Cyclone DDS, "
                                                        "which this build left out (MECHSIM_WITH_CYCLONEDDS=OFF)").what());
      return 2;
    }
  }
  try {
    for (const std::string& text : options.replays) {
      const ReplayRequest r = parse_replay_request(text);
      if (hosts.remote.count(r.node))
        throw config::ConfigError(scene.file, "participants." + r.node + ".host",
                                  "a replayed participant on the launcher's host: --replay of a participant on another host is not supported");
    }
  } catch (const config::ConfigError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  try {
    Run run(options, scene, *plan, std::move(hosts));
    return run.execute();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim launch: %s\n", e.what());
    return 1;
  }
}

}  // namespace mechsim::launch

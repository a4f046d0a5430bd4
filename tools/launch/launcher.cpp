#include "launcher.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <thread>

#include "agent_client.h"
#include "domain_lock.h"
#include "domain_readers.h"
#include "hosts.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/checkpoint.h"
#include "mechsim/cosim/composer.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/pacer.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/transport/backends.h"
#include "mechsim/transport/network_config.h"
#include "node_processes.h"
#include "replay_input.h"
#include "run_recording.h"
#include "run_security.h"
#include "paths.h"
#include "run_report.h"
#include "signal_compare.h"
#include "solver_health.h"
#include "stable_step.h"
#include "csv.h"
#include "json_io.h"
#include "plot.h"
#include "provenance.h"
#include "realtime_report.h"
#include "reference_accuracy.h"
#include "elapsed.h"

namespace mechsim::launch {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using nlohmann::json;

namespace {

std::atomic<int> g_interrupt{0};
void on_interrupt(int sig) { g_interrupt.store(sig); }

// The DDS lease of a multi-host run: a cut shorter than the partition grace must not make
// the participants forget each other (what was written meanwhile would be lost for good).
double lease_for(const config::Scene& scene) { return config::fault_timings(scene).dds_lease; }


std::string hex_id(std::uint64_t id) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(id));
  return buf;
}

struct NodeWatch {
  transport::StatusMessage last;
  bool seen = false;
  Clock::time_point last_seen{};
  double done_at_s = -1;  // since start, from the node's done status
};

// The outcome of the distributed part of a run.
struct RunOutcome {
  bool ok = false;
  int exit_code = 1;
  std::string failed_node;
  std::string reason;
  std::uint64_t failed_step = 0;
  double wall_time_s = 0.0;  // start command -> all nodes done
};

// One restart with rollback (docs/faults.md), for the summary.
struct RestartRecord {
  std::string node, exit;
  std::uint64_t last_step = 0;      // the dead node's last step (output log or heartbeat)
  std::uint64_t rollback_step = 0;  // the checkpoint every node went back to
  int generation = 0;
  double detected_s = 0;            // since the start command: the launcher saw the death
  double resumed_s = -1;            // every node held the checkpoint; resume sent
  double stepping_s = -1;           // every node's status past the checkpoint again
};

class Run {
 public:
  Run(const LaunchOptions& o, config::Scene& scene, cosim::ScenePlan& plan, HostLayout hosts)
      : opt_(o), scene_(scene), plan_(plan), hosts_(std::move(hosts)) {}

  int execute();

 private:
  RunOutcome run_nodes();
  void fail(RunOutcome& out, const std::string& node, const std::string& reason);
  std::uint64_t last_step_of(const std::string& node) const;
  std::string divergence_advice(const std::string& node) const;
  std::string divergence_advice_text(const std::string& node) const;
  void print_progress(double since_start, bool final_line);
  json summarise(const RunOutcome& out);

  const LaunchOptions& opt_;
  config::Scene& scene_;
  cosim::ScenePlan& plan_;
  std::uint64_t run_id_ = 0;
  std::string run_dir_;
  int domain_ = 0;
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<transport::ControlWriter> control_;
  std::unique_ptr<transport::StatusReader> status_;
  HostLayout hosts_;
  std::unique_ptr<AgentClient> agents_;  // multi-host runs; outlives processes_, which uses it
  std::vector<std::string> hand_back_problems_;
  NodeProcesses processes_;
  std::map<std::string, NodeWatch> watch_;
  std::vector<std::string> warnings_;
  bool tty_ = false;
  std::map<std::string, std::string> replay_tables_;  // node -> table its process replays
  std::unique_ptr<RunRecording> recording_;
  std::unique_ptr<DomainReaders> domain_readers_;  // who reads the nodes' topics (a user's recorder)
  std::map<std::string, std::vector<std::string>> node_args_;  // local nodes: their command line
  std::map<std::string, int> restarts_;                          // per node
  std::vector<RestartRecord> restart_log_;
  mutable std::optional<std::string> divergence_advice_;  // computed once (it runs a search)
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

// Names the connections that cross a coupling element (instability travels round the
// loop, so the node that noticed it first need not sit at the cut), else the diverged
// node's own connections, and suggests a smaller macro step.
std::string Run::divergence_advice(const std::string& node) const {
  if (divergence_advice_) return *divergence_advice_;
  divergence_advice_ = divergence_advice_text(node);
  return *divergence_advice_;
}

std::string Run::divergence_advice_text(const std::string& node) const {
  std::string cuts;
  for (const auto& c : scene_.connections)
    if (c.coupling)
      cuts += (cuts.empty() ? "" : ", ") + c.from + " -> " + c.to + " (" + c.key_path + ", coupling element)";
  if (cuts.empty())
    for (const auto& c : scene_.connections)
      if (c.from == node || c.to == node) cuts += (cuts.empty() ? "" : ", ") + c.from + " -> " + c.to + " (" + c.key_path + ")";
  char step[64], now[64];
  std::snprintf(step, sizeof step, "%g us", scene_.time.step / 4 * 1e6);
  std::snprintf(now, sizeof now, "%g us", scene_.time.step * 1e6);
  // An adaptive step lengthens its steps up to `max` as long as the estimate allows; a
  // stiff cut can be unstable long before its coupling error shows (docs/accuracy.md).
  if (scene_.time.adaptive)
    return ". The coupled run is unstable with an adaptive step of up to " + std::string(now) + " across " + cuts +
           "; lower time.max, e.g. --set 'time.max=" + step + "' (a fixed step's stable limit: mechsim bench SCENE --stability)";
  // The stable step, found by in-process runs of the resolved scene (stable_step.h),
  // halving the macro step; any sampled participant follows it.
  std::optional<double> stable;
  try {
    std::fprintf(stderr, "mechsim: the run diverged; looking for a stable macro step with in-process runs...\n");
    stable = find_stable_step_below(run_dir_ + "/scene.yaml", {}, scene_.time.step);
  } catch (const std::exception&) {
    // No search possible (e.g. a replayed node): the generic advice below.
  }
  if (stable) {
    char found[64];
    std::snprintf(found, sizeof found, "%.4g us", *stable * 1e6);
    return ". The coupled run is unstable at a macro step of " + std::string(now) + " across " + cuts +
           "; in-process runs of this scene are stable at " + found + ": try --step '" + found +
           "' (mechsim bench SCENE --stability bisects the limit per scheme; docs/accuracy.md)";
  }
  return ". The coupled run is unstable at a macro step of " + std::string(now) + " across " + cuts + "; try a smaller step, e.g. --step '" + step +
         "' (docs/nc-loop.md lists the measured limits)";
}

void Run::fail(RunOutcome& out, const std::string& node, const std::string& reason) {
  if (!out.reason.empty()) return;  // keep the first cause
  out.ok = false;
  out.failed_node = node;
  out.reason = reason;
  out.failed_step = last_step_of(node);
}

std::uint64_t Run::last_step_of(const std::string& node) const {
  auto it = watch_.find(node);
  std::uint64_t step = it != watch_.end() && it->second.seen ? it->second.last.header.step : 0;
  // The node's own output log knows its last step better than the last heartbeat did.
  try {
    const std::string path = run_dir_ + "/" + node + ".outputs.bin";
    if (!node.empty() && fs::exists(path)) {
      const std::size_t rows = cosim::read_output_log(path).rows();
      if (rows > 0) step = std::max<std::uint64_t>(step, rows - 1);
    }
  } catch (const std::exception&) {
    // a log too damaged to read: keep the heartbeat's figure
  }
  return step;
}

void Run::print_progress(double since_start, bool final_line) {
  if (!tty_ || !opt_.progress) return;
  std::uint64_t step = UINT64_MAX;
  for (const auto& [name, w] : watch_) step = std::min<std::uint64_t>(step, w.seen ? w.last.header.step : 0);
  double t = scene_.time.end;  // an adaptive run's grid grows in the nodes, not here: their heartbeats' t
  for (const auto& [name, w] : watch_) t = std::min(t, w.seen ? w.last.header.t : scene_.time.start);
  if (!plan_.grid()->is_adaptive()) t = plan_.grid()->time(std::min(step, plan_.grid()->steps()));
  const double rate = since_start > 0 ? static_cast<double>(step) / since_start : 0.0;
  const double rtf = since_start > 0 ? (t - scene_.time.start) / since_start : 0.0;
  std::string realtime;
  if (scene_.mode == config::RunMode::realtime) {
    long long missed = 0;
    double late = 0, p99 = 0;
    for (const auto& [name, w] : watch_) {
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

RunOutcome Run::run_nodes() {
  RunOutcome out;
  const auto launched = Clock::now();
  std::string scene_text;
  if (agents_) {
    std::ifstream in(run_dir_ + "/scene.yaml");
    scene_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  for (const auto& node : plan_.nodes()) {
    if (auto remote = hosts_.remote.find(node.name()); remote != hosts_.remote.end()) {
      // Its host's agent starts it with the same arguments, in a run folder of its own.
      const json request{{"type", node.type->name}, {"scene_yaml", scene_text},
                         {"run_folder", fs::path(run_dir_).filename().string()}, {"domain", domain_},
                         {"address", remote->second}, {"peers", hosts_.peers}, {"lease_s", lease_for(scene_)},
                         {"partition_grace_s", scene_.faults.partition_grace}, {"control_writer", control_->guid()}};
      processes_.start_remote(node.name(), remote->second, request.dump(), *agents_);
      watch_[node.name()] = {};
      continue;
    }
    const std::string exe = node_executable(node.type->name);
    std::vector<std::string> args{"--scene", run_dir_ + "/scene.yaml", "--node", node.name(), "--run-id", std::to_string(run_id_),
                                  "--domain", std::to_string(domain_), "--run-dir", run_dir_};
    // The node takes commands from this launcher's control writer only (docs/faults.md).
    if (const std::string guid = control_->guid(); !guid.empty()) {
      args.push_back("--control-writer");
      args.push_back(guid);
    }
    if (auto it = replay_tables_.find(node.name()); it != replay_tables_.end()) {
      args.push_back("--replay");
      args.push_back(it->second);
    }
    processes_.start(node.name(), exe, args, run_dir_ + "/" + node.name() + ".log", node_security_environment(scene_, node.name()));
    node_args_[node.name()] = args;
    watch_[node.name()] = {};
  }

  auto take_status = [&] {
    while (auto s = status_->take()) {
      if (s->header.run_id != run_id_) continue;
      auto it = watch_.find(s->node);
      if (it == watch_.end()) continue;
      if (s->warning == transport::NodeWarning::cannot_keep_up && it->second.last.warning != s->warning) {
        if (tty_ && opt_.progress) std::fprintf(stderr, "\n");
        std::fprintf(stderr, "mechsim: warning: node '%s' %s\n", s->node.c_str(), s->message.c_str());
        warnings_.push_back("node '" + s->node + "' " + s->message);
      }
      it->second.last = *s;
      it->second.seen = true;
      it->second.last_seen = Clock::now();
    }
  };
  // Restart with rollback (docs/faults.md): the nodes that died while the run was going
  // and may be restarted.
  std::vector<std::string> to_restart;
  auto check_exits = [&](bool running) {
    for (NodeProcess* p : processes_.poll()) {
      const auto& w = watch_[p->name];
      bool clean = !p->signalled && p->exit_code == 0;
      const config::ParticipantSpec* spec = scene_.find_participant(p->name);
      // Restarted when it died on a signal (killed, a crash, the OOM killer); a node that
      // exits with an error of its own (diverged, foreign data, ...) would fail again.
      const bool crashed = p->signalled;
      if (!clean && running && spec && spec->restart && p->host.empty() && crashed) {
        if (restarts_[p->name] < scene_.faults.restart_limit) {
          to_restart.push_back(p->name);
          continue;
        }
        fail(out, p->name, "node '" + p->name + "' " + p->describe_exit() + " after " + std::to_string(restarts_[p->name]) +
                               " restart(s): faults.restart_limit " + std::to_string(scene_.faults.restart_limit) + " reached");
        continue;
      }
      if (!clean || !running) {
        std::string reason = "node '" + p->name + "' " + p->describe_exit();
        std::string message = w.seen ? w.last.message : "";
        if (message.empty()) message = last_error_line(run_dir_ + "/" + p->name + ".log");
        // The status carries at most 256 characters: the node's log has the whole message.
        if (message.size() >= 250) {
          const std::string line = last_error_line(run_dir_ + "/" + p->name + ".log");
          if (const auto at = line.find(message.substr(0, 40)); at != std::string::npos) message = line.substr(at);
        }
        if (!message.empty()) reason += ": " + message;
        if (w.seen && transport::points_to_divergence(w.last.error)) reason += divergence_advice(p->name);
        fail(out, p->name, reason);
      }
    }
  };

  // Every node back to the newest checkpoint they all hold: the dead ones started again
  // from it, the live ones told to roll back; the run resumes once each holds it.
  transport::ControlMessage start;
  Clock::time_point started;
  std::int32_t generation = 0;
  auto roll_back = [&] {
    const double detected = seconds_since(started);
    std::vector<std::string> names;
    for (const auto& p : processes_.processes()) names.push_back(p.name);
    const auto common = cosim::common_checkpoint(run_dir_, names);
    const std::string dead = to_restart.front();
    if (!common) {
      fail(out, dead, "node '" + dead + "' " + processes_.find(dead).describe_exit() + " before every node held a checkpoint (the first is at step " +
                          std::to_string(scene_.faults.checkpoint_every) + ", faults.checkpoint_every): no restart");
      return;
    }
    ++generation;
    for (const auto& name : to_restart) {
      RestartRecord r;
      r.node = name;
      r.exit = processes_.find(name).describe_exit();
      r.last_step = last_step_of(name);
      r.rollback_step = *common;
      r.generation = generation;
      r.detected_s = detected;
      ++restarts_[name];
      if (tty_ && opt_.progress) std::fprintf(stderr, "\n");
      std::fprintf(stderr, "mechsim: node '%s' %s at step %llu: restart %d of %ld, every node back to step %llu\n", name.c_str(),
                   r.exit.c_str(), static_cast<unsigned long long>(r.last_step), restarts_[name], scene_.faults.restart_limit,
                   static_cast<unsigned long long>(*common));
      restart_log_.push_back(r);
    }
    to_restart.clear();
    transport::ControlMessage rollback = start;
    rollback.command = transport::ControlCommand::rollback;
    rollback.step = *common;
    rollback.generation = generation;
    control_->write(rollback);
    auto restart = [&](NodeProcess& p) {
      std::vector<std::string> args = node_args_.at(p.name);
      args.insert(args.end(), {"--resume", std::to_string(*common), "--generation", std::to_string(generation)});
      processes_.restart(p.name, args, run_dir_ + "/" + p.name + ".log", node_security_environment(scene_, p.name));
      watch_[p.name].last_seen = Clock::now();
      watch_[p.name].done_at_s = -1;  // it finishes again
    };
    // Every exited node, also one that finished (exit 0) before the rollback reached it.
    for (auto& p : processes_.processes())
      if (p.exited) restart(p);
    const auto asked = Clock::now();
    for (;;) {
      take_status();
      for (NodeProcess* p : processes_.poll()) {
        if (!p->signalled && p->exit_code == 0) {  // it finished before it saw the rollback
          restart(*p);
          continue;
        }
        fail(out, p->name, "node '" + p->name + "' " + p->describe_exit() + " during the rollback to step " +
                               std::to_string(*common) + " (see " + run_dir_ + "/" + p->name + ".log)");
        return;
      }
      bool all = true;
      for (const auto& [name, w] : watch_) all = all && w.last.back_at(*common, generation);
      if (all) break;
      if (g_interrupt) return;
      if (seconds_since(asked) > opt_.ready_timeout_s) {
        std::string late;
        for (const auto& [name, w] : watch_)
          if (!w.last.back_at(*common, generation)) late += (late.empty() ? "" : ", ") + name;
        fail(out, late, "nodes not back at step " + std::to_string(*common) + " after " + std::to_string(opt_.ready_timeout_s) + " s: " + late);
        return;
      }
      participant_->wait(std::chrono::milliseconds(2));
    }
    transport::ControlMessage resume = rollback;
    resume.command = transport::ControlCommand::resume;
    control_->write(resume);
    for (auto& r : restart_log_)
      if (r.generation == generation) r.resumed_s = seconds_since(started);
    for (auto& [name, w] : watch_) w.last_seen = Clock::now();
  };

  // 1. Every node ready (matched end to end with its partners).
  for (;;) {
    take_status();
    check_exits(false);
    if (!out.reason.empty()) return out;
    if (g_interrupt) {
      fail(out, "", "interrupted");
      out.exit_code = 130;
      return out;
    }
    bool all_ready = true;
    for (const auto& [name, w] : watch_) all_ready = all_ready && w.seen && w.last.state == transport::NodeState::ready;
    if (all_ready) break;
    if (seconds_since(launched) > opt_.ready_timeout_s) {
      std::string late;
      for (const auto& [name, w] : watch_)
        if (!w.seen || w.last.state != transport::NodeState::ready) late += (late.empty() ? "" : ", ") + name;
      fail(out, late, "nodes not ready after " + std::to_string(opt_.ready_timeout_s) + " s: " + late +
                          " (see their logs in " + run_dir_ + ")");
      return out;
    }
    participant_->wait(std::chrono::milliseconds(5));
  }

  // The recorder's readers exist since before the nodes: start only once each of them is
  // matched with its writer, or the first samples could miss the file.
  if (recording_ && !recording_->wait_matched(std::chrono::seconds(10))) {
    fail(out, "", "the recorder's readers did not match the nodes' writers within 10 s");
    return out;
  }
  // Every reader on the domain (a recorder the user started first) matched by the writer
  // it reads: each node reports how many it has matched (docs/recording.md).
  for (const auto since = Clock::now();;) {
    take_status();
    check_exits(false);
    if (!out.reason.empty()) return out;
    std::string late;
    const auto domain_readers = domain_readers_ ? domain_readers_->by_topic_and_type() : decltype(domain_readers_->by_topic_and_type()){};
    for (const auto& node : plan_.nodes()) {
      const auto found = domain_readers.find({node.topic, node.type->publishes->idl_name});
      const int readers = found == domain_readers.end() ? 0 : found->second;
      const transport::StatusMessage& s = watch_.at(node.name()).last;
      if (s.readers_matched < readers)
        late += (late.empty() ? "" : ", ") + node.name() + " (" + std::to_string(s.readers_matched) + " of " + std::to_string(readers) + ")";
    }
    if (late.empty()) break;
    if (seconds_since(since) > 10.0) {
      const std::string why = "the nodes' writers did not match every reader on the domain within 10 s: " + late +
                              "; a recorder may miss the first steps";
      std::fprintf(stderr, "mechsim: warning: %s\n", why.c_str());
      warnings_.push_back(why);
      break;
    }
    if (g_interrupt) break;
    participant_->wait(std::chrono::milliseconds(2));
  }

  // 2. Start, then watch until every node is done.
  const bool realtime = scene_.mode == config::RunMode::realtime;
  start = transport::ControlMessage{run_id_, transport::ControlCommand::start, scene_.time.end, scene_.time.step,
                                    realtime ? transport::RunMode::realtime : transport::RunMode::lockstep, scene_.rtf, 0, 0, 0, {}};
  // Real-time pacing counts from the start command: step 0 is due a moment after it is
  // sent, so that every node has it by then.
  if (realtime) start.start_wall_ns = cosim::Pacer::now_ns() + 50'000'000;
  control_->write(start);
  started = Clock::now();
  for (auto& [name, w] : watch_) w.last_seen = started;
  auto last_progress = Clock::now();
  for (;;) {
    take_status();
    for (auto& [name, w] : watch_)
      if (w.last.state == transport::NodeState::done && w.done_at_s < 0) w.done_at_s = seconds_since(started);
    check_exits(true);
    if (!out.reason.empty()) break;
    if (!to_restart.empty()) {
      roll_back();
      if (!out.reason.empty()) break;
      if (g_interrupt) continue;
    }
    // The run steps again once every node is past the checkpoint it went back to.
    if (!restart_log_.empty() && restart_log_.back().stepping_s < 0 && restart_log_.back().resumed_s >= 0) {
      bool past = true;
      for (const auto& [name, w] : watch_) past = past && w.last.state != transport::NodeState::ready && w.last.header.step > restart_log_.back().rollback_step;
      if (past)
        for (auto& r : restart_log_)
          if (r.generation == restart_log_.back().generation) r.stepping_s = seconds_since(started);
    }
    if (processes_.all_exited()) {
      out.ok = true;
      // The final statuses (done, with the solver statistics) may still be in flight.
      for (int i = 0; i < 20; ++i) {
        take_status();
        bool all = true;
        for (const auto& [name, w] : watch_) all = all && w.last.state == transport::NodeState::done;
        if (all) break;
        participant_->wait(std::chrono::milliseconds(5));
      }
      for (auto& [name, w] : watch_)
        if (w.last.state == transport::NodeState::done && w.done_at_s < 0) w.done_at_s = seconds_since(started);
      break;
    }
    if (g_interrupt) {
      fail(out, "", "interrupted by signal " + std::to_string(g_interrupt.load()));
      out.exit_code = 130;
      break;
    }
    // A node on another host that has gone silent for the partition grace: the network
    // between here and its host is cut (or the host is down). Name every such node.
    {
      std::string unreachable, first;
      for (auto& p : processes_.processes()) {
        const auto& w = watch_[p.name];
        if (p.exited || p.host.empty() || seconds_since(w.last_seen) <= config::fault_timings(scene_).silence_warning) continue;
        const auto* spec = scene_.find_participant(p.name);
        unreachable += (unreachable.empty() ? "" : ", ") + ("'" + p.name + "' on host " + spec->host + " (" + p.host + ")");
        if (seconds_since(w.last_seen) > scene_.faults.partition_grace && first.empty()) first = p.name;
      }
      if (!first.empty()) {
        char why[128];
        std::snprintf(why, sizeof why, ": no status for more than %g s (faults.partition_grace; docs/faults.md)", scene_.faults.partition_grace);
        fail(out, first, "unreachable: node " + unreachable + why);
      }
    }
    if (!out.reason.empty()) break;
    for (auto& p : processes_.processes()) {
      const auto& w = watch_[p.name];
      if (!p.exited && p.host.empty() && seconds_since(w.last_seen) > scene_.hang_timeout) {
        std::ostringstream why;
        // The last step is added once, by the failure report (from the node's output log).
        why << "node '" << p.name << "' hung: no status for " << scene_.hang_timeout << " s";
        fail(out, p.name, why.str());
      }
    }
    if (!out.reason.empty()) break;
    if (seconds_since(last_progress) > 0.2) {
      print_progress(seconds_since(started), false);
      last_progress = Clock::now();
    }
    participant_->wait(std::chrono::milliseconds(20));
  }
  out.wall_time_s = seconds_since(started);
  double done_max = 0;
  bool all_done = true;
  for (const auto& [name, w] : watch_) {
    all_done = all_done && w.done_at_s >= 0;
    done_max = std::max(done_max, w.done_at_s);
  }
  if (out.ok && all_done) out.wall_time_s = done_max;  // excludes process tear-down
  if (out.ok) {
    print_progress(out.wall_time_s, true);
  } else {
    if (tty_ && opt_.progress) std::fprintf(stderr, "\n");
    // Tell the others, then make sure: every process stops, none is left behind.
    transport::ControlMessage abort = start;
    abort.command = transport::ControlCommand::abort;
    control_->write(abort);
    processes_.stop_all(2.0);
  }
  return out;
}

// The solver figures of one node from its last status.
NodeSolverFigures solver_figures(const config::ParticipantSpec& spec, const transport::StatusMessage& last, long macro_steps,
                                 double macro_step) {
  NodeSolverFigures f;
  f.method = spec.solver.method;
  f.steps = last.solver_steps;
  f.rhs_evals = last.rhs_evals;
  f.error_test_failures = last.error_test_failures;
  f.nonlinear_failures = last.nonlinear_failures;
  f.roots_found = last.roots_found;
  f.last_step = last.last_step_size;
  f.last_order = last.last_order;
  f.macro_steps = macro_steps;
  f.macro_step = macro_step;
  return f;
}

// One line per node with its integrator statistics, and the stiffness hints.
void print_solver_health(const json& nodes) {
  for (const auto& [name, n] : nodes.items()) {
    const json& s = n["solver"];
    if (s.value("steps", 0LL) == 0) continue;  // a node without states (or no status seen)
    std::printf("  solver %-10s %s: %lld steps (%.1f per macro step), %lld error-test / %lld convergence failures, %lld roots, last step %.3g s, order %lld\n",
                name.c_str(), s.value("method", std::string("?")).c_str(), s.value("steps", 0LL),
                s.value("steps_per_macro_step", 0.0), s.value("error_test_failures", 0LL), s.value("nonlinear_failures", 0LL),
                s.value("roots_found", 0LL), s.value("last_step_s", 0.0), s.value("last_order", 0LL));
  }
  for (const auto& [name, n] : nodes.items())
    if (n["solver"].contains("stiffness_hint"))
      std::printf("  hint: node '%s': %s\n", name.c_str(), n["solver"]["stiffness_hint"].get<std::string>().c_str());
}

json Run::summarise(const RunOutcome& out) {
  json s;
  s["schema_version"] = tools::schema_version;
  s["provenance"] = tools::provenance(scene_.file);
  s["scene"] = scene_.name;
  s["scene_file"] = scene_.file;
  s["run_id"] = hex_id(run_id_);
  s["run_dir"] = run_dir_;
  s["domain_id"] = domain_;
  s["dds_vendor"] = scene_.vendor;  // the launcher's own participant
  if (!scene_.security_dir.empty()) {
    s["dds_security"] = scene_.security_dir;
    s["dds_protection"] = scene_.security_protection;
  }
  s["mode"] = config::to_string(scene_.mode);
  s["redundant_samples"] = scene_.faults.redundant();
  if (scene_.checkpointing()) {
    json restarts = json::array();
    for (const auto& r : restart_log_)
      restarts.push_back({{"node", r.node}, {"exit", r.exit}, {"last_step", r.last_step}, {"rollback_step", r.rollback_step},
                          {"generation", r.generation}, {"detected_s", r.detected_s}, {"resumed_s", r.resumed_s},
                          {"stepping_s", r.stepping_s},
                          {"kill_to_resume_s", r.resumed_s >= 0 ? r.resumed_s - r.detected_s : -1.0},
                          {"kill_to_stepping_s", r.stepping_s >= 0 ? r.stepping_s - r.detected_s : -1.0}});
    s["restart"] = {{"checkpoint_every", scene_.faults.checkpoint_every}, {"restart_limit", scene_.faults.restart_limit},
                    {"restarts", restarts}};
  }
  s["status"] = out.ok ? "ok" : "failed";
  s["macro_step_s"] = scene_.time.step;
  s["simulated_time_s"] = scene_.time.end - scene_.time.start;
  // An adaptive run's steps are those its nodes logged (the launcher's own grid never grows).
  std::uint64_t steps = plan_.grid()->steps();
  if (plan_.grid()->is_adaptive()) {
    std::vector<double> instants;
    try {
      instants = cosim::run_instants(plan_, run_dir_);
    } catch (const std::exception&) {
      // a node that died before its log had a header: no instants
    }
    steps = instants.empty() ? 0 : instants.size() - 1;
    s["adaptive_step"] = adaptive_step_summary(*scene_.time.adaptive, instants);
  }
  s["steps"] = steps;
  if (!plan_.scheduled_events().empty()) {  // where the grid lands a boundary (docs/accuracy.md)
    nlohmann::json events = nlohmann::json::array();
    for (const auto& e : plan_.scheduled_events()) events.push_back({{"participant", e.participant}, {"t_s", e.t}});
    s["scheduled_events"] = events;
  }
  s["wall_time_s"] = out.wall_time_s;
  s["steps_per_second"] = out.wall_time_s > 0 ? static_cast<double>(steps) / out.wall_time_s : 0.0;
  s["real_time_factor"] = out.wall_time_s > 0 ? (scene_.time.end - scene_.time.start) / out.wall_time_s : 0.0;
  if (!out.ok)
    s["failure"] = {{"node", out.failed_node}, {"last_step", out.failed_step}, {"reason", out.reason}};
  json nodes = json::object();
  for (auto& p : processes_.processes()) {
    const auto& w = watch_[p.name];
    const auto* spec = scene_.find_participant(p.name);
    nodes[p.name] = {{"type", spec->type},
                     {"vendor", spec->vendor},
                     {"host", p.host.empty() ? (hosts_.launcher_host.empty() ? "local" : hosts_.launcher_host) : spec->host},
                     {"exit", p.describe_exit()},
                     {"last_step", w.seen ? w.last.header.step : 0},
                     {"solver",
                      {{"steps", w.last.solver_steps},
                       {"rhs_evals", w.last.rhs_evals},
                       {"error_test_failures", w.last.error_test_failures},
                       {"nonlinear_failures", w.last.nonlinear_failures},
                       {"roots_found", w.last.roots_found},
                       {"last_step_s", w.last.last_step_size},
                       {"last_order", w.last.last_order}}},
                     {"log", run_dir_ + "/" + p.name + ".log"}};
    // Integrator health (solver_health.h): steps per macro step and the stiffness hint.
    const NodeSolverFigures health = solver_figures(*spec, w.last, w.seen ? static_cast<long>(w.last.header.step) : 0, scene_.time.step);
    nodes[p.name]["solver"]["method"] = health.method;
    nodes[p.name]["solver"]["steps_per_macro_step"] = steps_per_macro_step(health);
    if (auto hint = stiffness_hint(health)) nodes[p.name]["solver"]["stiffness_hint"] = *hint;
  }
  s["nodes"] = nodes;
  if (hosts_.multi_host) {
    json agents = json::object();
    if (agents_)
      for (const auto& [address, hello] : agents_->agents()) agents[address] = json::parse(hello, nullptr, false);
    s["hosts"] = {{"launcher_host", hosts_.launcher_host}, {"launcher_address", hosts_.launcher_address},
                  {"addresses", hosts_.address}, {"agents", agents}, {"hand_back_problems", hand_back_problems_}};
  }
  // Events the nodes reported (lift-off, landing, ...), from <node>.events.jsonl.
  json events = json::array();
  for (auto& p : processes_.processes()) {
    std::ifstream in(run_dir_ + "/" + p.name + ".events.jsonl");
    for (std::string line; std::getline(in, line);) {
      json e = json::parse(line, nullptr, false);
      if (e.is_discarded()) continue;
      e["node"] = p.name;
      events.push_back(e);
    }
  }
  s["events"] = events;
  std::vector<std::string> node_names;
  for (const auto& p : processes_.processes()) node_names.push_back(p.name);
  if (scene_.mode == config::RunMode::realtime) s["realtime"] = realtime_summary(scene_, *plan_.grid(), node_names, run_dir_, warnings_);
  s["process_realtime"] = process_settings_summary(node_names, run_dir_);
  return s;
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
  std::random_device rd;
  run_id_ = (static_cast<std::uint64_t>(rd()) << 32) ^ rd() ^ static_cast<std::uint64_t>(::getpid());
  run_dir_ = (fs::path(opt_.runs_dir) / (scene_.name + "-" + hex_id(run_id_).substr(8))).string();
  fs::create_directories(run_dir_);
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
  std::optional<DomainLock> lock;
  if (scene_.domain_id) {
    domain_ = *scene_.domain_id;
  } else {
    lock.emplace(DomainLock::acquire());
    domain_ = lock->domain_id();
  }
  if (hosts_.multi_host) {
    // The hosts' interfaces and unicast peers for both vendors, generated from the scene,
    // for the launcher, its recorder and the local nodes (the agents write their own).
    set_environment(write_unicast_dds_files(run_dir_ + "/dds", {hosts_.launcher_address, hosts_.peers, lease_for(scene_)}));
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
    agents_ = std::make_unique<AgentClient>(*participant_, run_id_, run_dir_);
    std::vector<std::string> addresses;
    for (const auto& [node, address] : hosts_.remote)
      if (std::find(addresses.begin(), addresses.end(), address) == addresses.end()) addresses.push_back(address);
    std::fprintf(stderr, "mechsim: multi-host run: launcher on %s (%s), waiting for the agents on %s\n",
                 hosts_.launcher_host.c_str(), hosts_.launcher_address.c_str(), join(addresses, ", ").c_str());
    const auto missing = agents_->wait_for_agents(addresses, opt_.ready_timeout_s, [] { return g_interrupt.load() != 0; });
    if (!missing.empty()) {
      std::fprintf(stderr, "mechsim launch: no mechsim agent answered from %s on domain %d within %g s: start "
                           "`mechsim agent --domain %d --address ADDRESS --peers %s` on each of those hosts (docs/hosts.md)\n",
                   join(missing, ", ").c_str(), domain_, opt_.ready_timeout_s, domain_, hosts_.launcher_address.c_str());
      return 1;
    }
  }

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
  recording_ = RunRecording::start(plan_, domain_, run_dir_);
  RunOutcome out = run_nodes();
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
  json summary = summarise(out);
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

  if (out.ok) {
    // Compare with the monolithic reference on the macro-step grid (an adaptive run's: the
    // instants its nodes logged).
    cosim::ScenePlan reference_plan = cosim::ScenePlan::build(scene_);
    cosim::ReferenceRun ref = cosim::run_reference_at(reference_plan, cosim::run_instants(plan_, run_dir_));
    const cosim::ReferenceAccuracy ref_accuracy = cosim::estimate_reference_error(scene_, ref);
    std::map<std::string, cosim::OutputLog> logs;
    for (const auto& node : plan_.nodes())
      logs[node.name()] = cosim::read_output_log(run_dir_ + "/" + node.name() + ".outputs.bin");
    // An adaptive step without time.scales measured each signal against its range so far,
    // small while it first rises: the ranges of this run, to write in the scene.
    if (const auto& a = scene_.time.adaptive; a && a->scales.empty()) {
      json suggested = json::object();
      for (const auto& [participant, field] : plan_.scaled_quantities()) {
        const auto& log = logs.at(participant);
        const int c = log.column(field);
        if (c < 0) continue;
        if (const double range = cosim::finite_range(log.data[static_cast<std::size_t>(c)]); range > 0)
          suggested[participant][field] = range;
      }
      summary["adaptive_step"]["suggested_scales"] = suggested;
    }
    const auto& t = ref.log.data[0];
    auto cosim_series = [&](const config::SignalRef& r) -> std::span<const double> {
      const auto& log = logs.at(r.participant);
      int c = log.column(r.output);
      return c < 0 ? std::span<const double>{} : std::span<const double>(log.data[c]);
    };
    auto reference_series = [&](const config::SignalRef& r) -> std::span<const double> {
      int c = ref.log.column(r.full_name());
      return c < 0 ? std::span<const double>{} : std::span<const double>(ref.log.data[c]);
    };
    json signals = json::object();
    std::vector<std::string> csv_header{"t"};
    std::vector<std::vector<double>> csv_columns{t};
    plot::Figure figure;
    figure.title = scene_.name + ": co-simulation against the reference";
    for (const auto& sig : scene_.compare) {
      auto c = cosim_series(sig);
      auto r = reference_series(sig);
      if (c.size() != r.size()) throw std::runtime_error(sig.full_name() + ": node log has " + std::to_string(c.size()) +
                                                         " rows, reference " + std::to_string(r.size()));
      SignalError e = compare_signal(t, c, r);
      const ErrorCause cause = classify_error(t, c, r);
      const auto& node = plan_.node(sig.participant);
      signals[sig.full_name()] = {{"unit", node.block->outputs()[node.block->output_index(sig.output)].unit},
                                  {"max_abs_error", e.max_abs}, {"max_rel_error", e.max_rel},
                                  {"rms_abs_error", e.rms_abs}, {"rms_rel_error", e.rms_rel},
                                  {"reference_range", e.range}, {"t_of_max_error_s", e.t_of_max},
                                  {"finite", e.finite},
                                  {"one_step_late", cause.one_step_late},
                                  {"max_abs_error_shifted_one_step", cause.max_abs_shifted},
                                  {"max_abs_error_at_jump", cause.jump},
                                  {"t_jump_s", cause.jump ? json(cause.t_jump) : json(nullptr)},
                                  {"reference_jumps", cause.jumps},
                                  {"max_abs_error_away_from_jumps", cause.max_abs_away_from_jumps}};
      csv_header.push_back(sig.full_name());
      csv_columns.emplace_back(c.begin(), c.end());
      csv_header.push_back(sig.full_name() + ".reference");
      csv_columns.emplace_back(r.begin(), r.end());
      plot::Panel panel;
      panel.title = sig.full_name();
      panel.xlabel = "t [s]";
      panel.ylabel = sig.output + " [" + signals[sig.full_name()]["unit"].get<std::string>() + "]";
      panel.series.push_back({"reference", std::vector<double>(t.begin(), t.end()), std::vector<double>(r.begin(), r.end()), "lines"});
      panel.series.push_back({"co-simulation", std::vector<double>(t.begin(), t.end()), std::vector<double>(c.begin(), c.end()), "dashed"});
      figure.panels.push_back(panel);
      // At this scale the two curves lie on each other: the difference gets its own panel.
      plot::Panel error_panel;
      error_panel.title = sig.full_name() + ": co-simulation - reference";
      error_panel.xlabel = "t [s]";
      error_panel.ylabel = "error [" + signals[sig.full_name()]["unit"].get<std::string>() + "]";
      std::vector<double> difference(c.size());
      for (std::size_t k = 0; k < c.size(); ++k) difference[k] = c[k] - r[k];
      error_panel.series.push_back({"error", std::vector<double>(t.begin(), t.end()), std::move(difference), "lines"});
      figure.panels.push_back(error_panel);
    }
    summary["signals"] = signals;
    const SeriesLookup reference_lookup = reference_series;
    summary["report"] = report_figures(scene_, t, cosim_series, &reference_lookup);
    json ref_events = json::object();
    for (const auto& e : ref.events) ref_events[e.kind] = ref_events.value(e.kind, 0) + 1;
    summary["reference"] = {{"rtol", ref.rtol}, {"wall_time_s", ref.wall_time_s}, {"solver", solver_stats_json(ref.stats)},
                            {"event_counts", ref_events},
                            {"accuracy", reference_accuracy_json(scene_, ref, ref_accuracy)}};
    tools::write_csv(run_dir_ + "/signals.csv", csv_header, csv_columns);
    summary["files"] = {{"signals_csv", run_dir_ + "/signals.csv"}};
    if (opt_.plots && !figure.panels.empty()) {
      std::string why;
      if (plot::write_png(figure, run_dir_ + "/signals.png", &why))
        summary["files"]["signals_png"] = run_dir_ + "/signals.png";
      else
        std::fprintf(stderr, "mechsim: no plot: %s\n", why.c_str());
    }
  }
  if (opt_.plots && summary.contains("realtime")) {
    std::string why;
    const auto pngs = write_lateness_plots(summary["realtime"], scene_.time.step / scene_.rtf, run_dir_, &why);
    for (const auto& png : pngs) summary["files"]["lateness_png"].push_back(png);
    if (pngs.empty() && !why.empty()) std::fprintf(stderr, "mechsim: no lateness plot: %s\n", why.c_str());
  }
  tools::write_json_file(run_dir_ + "/summary.json", summary);
  if (!opt_.json_path.empty()) tools::write_json_file(opt_.json_path, summary);

  // Human summary.
  if (out.ok) {
    char of_length[160];
    if (const json* a = summary.contains("adaptive_step") ? &summary["adaptive_step"] : nullptr; a && (*a)["shortest_s"].is_number())
      std::snprintf(of_length, sizeof of_length, "adaptive steps of %g .. %g s (tolerance %g)", (*a)["shortest_s"].get<double>(),
                    (*a)["longest_s"].get<double>(), (*a)["tolerance"].get<double>());
    else
      std::snprintf(of_length, sizeof of_length, "steps of %g s", scene_.time.step);
    std::printf("run %s of '%s': %llu %s in %.3f s wall: %.0f steps/s, real-time factor %.2f\n",
                hex_id(run_id_).c_str(), scene_.name.c_str(), static_cast<unsigned long long>(summary["steps"].get<std::uint64_t>()),
                of_length, out.wall_time_s, summary["steps_per_second"].get<double>(), summary["real_time_factor"].get<double>());
    for (auto& [name, e] : summary["signals"].items()) {
      const std::string unit = e["unit"].get<std::string>();
      char at[48] = "";
      if (e["max_abs_error"].get<double>() > 0) std::snprintf(at, sizeof at, " at t = %.6g s", e["t_of_max_error_s"].get<double>());
      std::printf("  %-32s max |error| %.3g %s (%.3g %% of range)%s, rms %.3g\n", name.c_str(),
                  e["max_abs_error"].get<double>(), unit.c_str(), 100 * e["max_rel_error"].get<double>(), at,
                  e["rms_abs_error"].get<double>());
      // A known artefact of the coupling: say which, and what the error is without it.
      const double range = e["reference_range"].get<double>();
      auto percent = [&](double v) { return range > 0 ? 100 * v / range : 0.0; };
      if (e.value("max_abs_error_at_jump", false))
        std::printf("  %-32s   at a jump of the reference (t = %.6g s) that a Jacobi edge crosses one macro step late;"
                    " away from the %d jump(s): max |error| %.3g %s (%.3g %%)\n", "", e["t_jump_s"].get<double>(),
                    e["reference_jumps"].get<int>(), e["max_abs_error_away_from_jumps"].get<double>(), unit.c_str(),
                    percent(e["max_abs_error_away_from_jumps"].get<double>()));
      else if (e.value("one_step_late", false))
        std::printf("  %-32s   the co-simulation is the reference one macro step late (a Jacobi edge): shifted by one step,"
                    " max |difference| %.3g %s\n", "", e["max_abs_error_shifted_one_step"].get<double>(), unit.c_str());
    }
    print_figures(summary["report"]);
    print_realtime_summary(summary);
    if (!summary["events"].empty()) {
      std::map<std::string, int> counts;
      for (const auto& e : summary["events"]) ++counts[e["node"].get<std::string>() + "." + e.value("kind", "?")];
      for (const auto& [kind, n] : counts)
        std::printf("  events: %d x %s (reference: %d; details in the summary JSON)\n", n, kind.c_str(),
                    summary["reference"]["event_counts"].value(kind, 0));
    }
    print_solver_health(summary["nodes"]);
    if (summary.contains("adaptive_step") && summary["adaptive_step"].contains("suggested_scales")) {
      std::string scales;
      for (const auto& [participant, fields] : summary["adaptive_step"]["suggested_scales"].items()) {
        std::string inner;
        for (const auto& [field, range] : fields.items()) {
          char buf[96];
          std::snprintf(buf, sizeof buf, "%s%s: %.3g", inner.empty() ? "" : ", ", field.c_str(), range.get<double>());
          inner += buf;
        }
        scales += (scales.empty() ? "" : ", ") + participant + ": {" + inner + "}";
      }
      std::printf("  adaptive step without time.scales: each signal's error was measured against its range so far, small while it\n"
                  "    first rises (docs/accuracy.md). This run's ranges (SI), to write in the scene's time section:\n"
                  "    scales: {%s}\n", scales.c_str());
    }
    std::printf("  run folder: %s\n", run_dir_.c_str());
    return 0;
  }
  std::fprintf(stderr, "mechsim: run failed: %s%s\n", out.reason.c_str(),
               out.failed_node.empty() || out.failed_node.find(',') != std::string::npos
                   ? ""
                   : (" (last step " + std::to_string(out.failed_step) + ")").c_str());
  print_solver_health(summary["nodes"]);
  std::fprintf(stderr, "mechsim: all node processes stopped; logs in %s\n", run_dir_.c_str());
  return out.exit_code;
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

int launch(const LaunchOptions& options) {
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  config::Scene scene;
  std::optional<cosim::ScenePlan> plan;
  std::vector<std::string> overrides = options.overrides;  // the user's, and those the launcher adds
  try {
    scene = config::load_scene(options.scene_path, overrides);
    if (!options.dds_layout.empty()) {
      std::vector<std::string> names;
      for (const auto& p : scene.participants) names.push_back(p.name);
      for (auto& o : dds_layout_overrides(names, options.dds_layout)) overrides.push_back(std::move(o));
      scene = config::load_scene(options.scene_path, overrides);
    }
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
  HostLayout hosts;
  try {
    hosts = plan_hosts(scene);
    if (hosts.multi_host && scene.faults.redundant_samples == "auto") {
      // Across a network packets get lost: every sample goes twice (docs/faults.md). The
      // resolved scene in the run folder carries the decision to every node.
      overrides.push_back("faults.redundant_samples=true");
      scene = config::load_scene(options.scene_path, overrides);
      plan.emplace(cosim::ScenePlan::build(scene));
    }
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

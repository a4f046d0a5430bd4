#include "mechsim/cosim/supervisor.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "mechsim/cosim/checkpoint.h"
#include "mechsim/cosim/node_end_record.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/pacer.h"

namespace mechsim::cosim {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

void NodeHost::restart(const std::string& node, std::uint64_t, std::int32_t) {
  throw std::logic_error("restart of node '" + node + "': its host cannot restart nodes");
}

bool is_rolled_back(const transport::StatusMessage& status, std::uint64_t step, std::int32_t generation) {
  return status.back_at(step, generation);
}

bool is_cannot_keep_up_warning(const transport::StatusMessage& status) {
  return status.warning == transport::NodeWarning::cannot_keep_up;
}

bool is_divergence(const transport::StatusMessage& status) { return transport::points_to_divergence(status.error); }

Supervisor::Supervisor(transport::Participant& participant, transport::ControlWriter& control, transport::StatusReader& status,
                       std::vector<NodeHost*> hosts, SupervisorOptions options, SupervisorHooks hooks)
    : participant_(participant), control_(control), status_(status), hosts_(std::move(hosts)), opt_(std::move(options)),
      hooks_(std::move(hooks)) {
  for (NodeHost* host : hosts_)
    for (const auto& node : host->nodes()) {
      nodes_.push_back(node);
      host_of_[node] = host;
    }
}

NodeHost& Supervisor::host_of(const std::string& node) const {
  auto it = host_of_.find(node);
  if (it == host_of_.end()) throw std::logic_error("no host runs node '" + node + "'");
  return *it->second;
}

void Supervisor::say(const std::string& line) const {
  if (hooks_.say) hooks_.say(line);
}

void Supervisor::pump() {
  for (NodeHost* host : hosts_) host->pump();
}

double Supervisor::since_start() const { return seconds_since(started_); }

void Supervisor::fail(const std::string& node, const std::string& reason, bool exit_says_diverged) {
  if (!out_.reason.empty()) return;  // keep the first cause
  out_.ok = false;
  out_.failed_node = node;
  out_.reason = reason;
  // The exit code says so even when the node's failed status (best effort) was lost.
  const auto it = watch_.find(node);
  out_.diverged = exit_says_diverged || (it != watch_.end() && it->second.seen && is_divergence(it->second.last));
  out_.failed_step = last_step_of(node);
}

std::uint64_t Supervisor::last_step_of(const std::string& node) const {
  auto it = watch_.find(node);
  std::uint64_t step = it != watch_.end() && it->second.seen ? it->second.last.header.step : 0;
  // The node's own output log knows its last step better than the last heartbeat did.
  try {
    const std::string path = opt_.run_dir + "/" + node + ".outputs.bin";
    if (!node.empty() && !opt_.run_dir.empty() && std::filesystem::exists(path)) {
      const std::size_t rows = read_output_log(path).rows();
      if (rows > 0) step = std::max<std::uint64_t>(step, rows - 1);
    }
  } catch (const std::exception&) {
    // a log too damaged to read: keep the heartbeat's figure
  }
  return step;
}

void Supervisor::take_status() {
  pump();
  while (auto s = status_.take()) {
    if (s->header.run_id != opt_.run_id) continue;
    auto it = watch_.find(s->node);
    if (it == watch_.end()) continue;
    if (is_cannot_keep_up_warning(*s) && !is_cannot_keep_up_warning(it->second.last)) {
      const std::string warning = "node '" + s->node + "' " + s->message;
      say("warning: " + warning);
      warnings_.push_back(warning);
    }
    it->second.last = *s;
    it->second.seen = true;
    it->second.last_seen = Clock::now();
  }
}

void Supervisor::check_exits(bool running) {
  std::vector<NodeExit> exits;
  for (NodeHost* host : hosts_)
    for (auto& e : host->poll()) exits.push_back(std::move(e));
  if (!exits.empty()) take_status();  // a final status may carry the message
  for (const NodeExit& e : exits) {
    NodeHost& host = host_of(e.node);
    const bool restartable = std::find(opt_.restartable.begin(), opt_.restartable.end(), e.node) != opt_.restartable.end();
    // Restarted when it died on a signal (killed, a crash, the OOM killer); a node that
    // exits with an error of its own (diverged, foreign data, ...) would fail again.
    if (!e.clean && running && restartable && host.can_restart(e.node) && e.crashed) {
      if (restarts_[e.node] < opt_.restart_limit) {
        to_restart_.push_back(e.node);
        continue;
      }
      fail(e.node, "node '" + e.node + "' " + host.describe_exit(e.node) + " after " + std::to_string(restarts_[e.node]) +
                       " restart(s): faults.restart_limit " + std::to_string(opt_.restart_limit) + " reached");
      continue;
    }
    if (e.clean && running && !e.reached_end && !reached_end(e.node)) {
      // Exit code 0 without the last step (an FMU's exit(0) in its step): the run is short.
      fail(e.node, "node '" + e.node + "' ended early: " + host.describe_exit(e.node) + " at step " +
                       std::to_string(last_step_of(e.node)) + of_last_step() + ", before its last step; the run is incomplete");
      continue;
    }
    if (!e.clean || !running) {
      const NodeWatch& w = watch_[e.node];
      std::string reason = "node '" + e.node + "' " + host.describe_exit(e.node);
      std::string message = w.seen ? w.last.message : "";
      if (hooks_.exit_message) message = hooks_.exit_message(e.node, message);
      if (!message.empty()) reason += ": " + message;
      fail(e.node, reason, e.diverged);
    }
  }
}

// A node that exited with code 0 finished when it wrote its end record (node_end_record.h)
// or said "done"; a remote node's record is on its host until the hand-back, so its
// status, which may still be in flight, is waited for a moment.
bool Supervisor::reached_end(const std::string& node) {
  if (opt_.run_dir.empty() || read_node_end_record(opt_.run_dir, node)) return true;
  const auto done = [&] { return watch_[node].seen && watch_[node].last.state == transport::NodeState::done; };
  const auto asked = Clock::now();
  while (!done() && host_of(node).remote(node) && seconds_since(asked) < 2.0) {
    participant_.wait(std::chrono::milliseconds(5));
    take_status();
  }
  return done();
}

std::string Supervisor::of_last_step() const {
  return opt_.last_step > 0 ? " of " + std::to_string(opt_.last_step) : "";
}

std::uint64_t Supervisor::reached_step(const std::string& node) const {
  if (const auto end = read_node_end_record(opt_.run_dir, node)) return end->step;
  return last_step_of(node);
}

// Every node back to the newest checkpoint they all hold: the dead ones started again
// from it, the live ones told to roll back; the run resumes once each holds it.
void Supervisor::roll_back() {
  const double detected = since_start();
  const auto common = common_checkpoint(opt_.run_dir, nodes_);
  const std::string dead = to_restart_.front();
  if (!common) {
    fail(dead, "node '" + dead + "' " + host_of(dead).describe_exit(dead) + " before every node held a checkpoint (the first is at step " +
                   std::to_string(opt_.checkpoint_every) + ", faults.checkpoint_every): no restart");
    return;
  }
  ++generation_;
  for (const auto& name : to_restart_) {
    RestartRecord r;
    r.node = name;
    r.exit = host_of(name).describe_exit(name);
    r.last_step = last_step_of(name);
    r.rollback_step = *common;
    r.generation = generation_;
    r.detected_s = detected;
    ++restarts_[name];
    char line[256];
    std::snprintf(line, sizeof line, "node '%s' %s at step %llu: restart %d of %d, every node back to step %llu", name.c_str(),
                  r.exit.c_str(), static_cast<unsigned long long>(r.last_step), restarts_[name], opt_.restart_limit,
                  static_cast<unsigned long long>(*common));
    say(line);
    restart_log_.push_back(r);
  }
  to_restart_.clear();
  transport::ControlMessage rollback = start_;
  rollback.command = transport::ControlCommand::rollback;
  rollback.step = *common;
  rollback.generation = generation_;
  control_.write(rollback);
  auto restart = [&](const std::string& node) {
    host_of(node).restart(node, *common, generation_);
    watch_[node].last_seen = Clock::now();
    watch_[node].done_at_s = -1;  // it finishes again
  };
  // Every exited node, also one that finished (exit 0) before the rollback reached it.
  for (const auto& node : nodes_)
    if (host_of(node).exited(node)) restart(node);
  const auto asked = Clock::now();
  for (;;) {
    take_status();
    for (NodeHost* host : hosts_)
      for (const NodeExit& e : host->poll()) {
        if (e.clean) {  // it finished before it saw the rollback
          restart(e.node);
          continue;
        }
        fail(e.node, "node '" + e.node + "' " + host->describe_exit(e.node) + " during the rollback to step " + std::to_string(*common) +
                         " (see " + opt_.run_dir + "/" + e.node + ".log)");
        return;
      }
    bool all = true;
    for (const auto& [name, w] : watch_) all = all && is_rolled_back(w.last, *common, generation_);
    if (all) break;
    if (hooks_.interrupted && hooks_.interrupted()) return;
    if (seconds_since(asked) > opt_.ready_timeout_s) {
      std::vector<std::string> late;
      for (const auto& [name, w] : watch_)
        if (!is_rolled_back(w.last, *common, generation_)) late.push_back(name);
      fail(join_names(late), "nodes not back at step " + std::to_string(*common) + " after " + std::to_string(opt_.ready_timeout_s) +
                                 " s: " + join_names(late));
      return;
    }
    participant_.wait(std::chrono::milliseconds(2));
  }
  transport::ControlMessage resume = rollback;
  resume.command = transport::ControlCommand::resume;
  control_.write(resume);
  for (auto& r : restart_log_)
    if (r.generation == generation_) r.resumed_s = since_start();
  for (auto& [name, w] : watch_) w.last_seen = Clock::now();
}

// A node on another host that has gone silent for the partition grace: the network between
// here and its host is cut (or the host is down); a local node silent for the hang timeout hung.
void Supervisor::watch_silence() {
  std::string unreachable, first;
  for (const auto& node : nodes_) {
    const NodeHost& host = host_of(node);
    const double silent = seconds_since(watch_[node].last_seen);
    if (host.exited(node) || !host.remote(node) || silent <= opt_.fault_timings.silence_warning) continue;
    unreachable += (unreachable.empty() ? "" : ", ") + ("'" + node + "' " + host.placement(node));
    if (silent > opt_.fault_timings.partition_grace && first.empty()) first = node;
  }
  if (!first.empty()) {
    char why[128];
    std::snprintf(why, sizeof why, ": no status for more than %g s (faults.partition_grace; docs/faults.md)", opt_.fault_timings.partition_grace);
    fail(first, "unreachable: node " + unreachable + why);
  }
  if (!out_.reason.empty()) return;
  for (const auto& node : nodes_) {
    const NodeHost& host = host_of(node);
    if (!host.exited(node) && !host.remote(node) && seconds_since(watch_[node].last_seen) > opt_.hang_timeout_s) {
      char why[64];
      std::snprintf(why, sizeof why, "%g", opt_.hang_timeout_s);
      // The last step is added once, by the failure report (from the node's output log).
      fail(node, "node '" + node + "' hung: no status for " + why + " s");
    }
  }
}

// Every node ready (matched end to end with its partners).
bool Supervisor::wait_ready() {
  const auto launched = Clock::now();
  for (;;) {
    take_status();
    check_exits(false);
    if (!out_.reason.empty()) return false;
    if (hooks_.interrupted && hooks_.interrupted()) {
      fail("", "interrupted");
      out_.exit_code = 130;
      return false;
    }
    bool all_ready = true;
    for (const auto& [name, w] : watch_) all_ready = all_ready && w.seen && w.last.state == transport::NodeState::ready;
    if (all_ready) return true;
    if (seconds_since(launched) > opt_.ready_timeout_s) {
      std::vector<std::string> late;
      for (const auto& [name, w] : watch_)
        if (!w.seen || w.last.state != transport::NodeState::ready) late.push_back(name);
      fail(join_names(late), "nodes not ready after " + std::to_string(opt_.ready_timeout_s) + " s: " + join_names(late) + opt_.not_ready_hint);
      return false;
    }
    participant_.wait(std::chrono::milliseconds(5));
  }
}

// The recorder's readers exist since before the nodes: start only once each of them is
// matched with its writer, or the first samples could miss the file. Then every reader on
// the domain (a recorder the user started first) matched by the writer it reads.
bool Supervisor::wait_readers() {
  if (hooks_.recorder_matched)
    if (std::string why = hooks_.recorder_matched(); !why.empty()) {
      fail("", why);
      return false;
    }
  if (!hooks_.unmatched_readers) return true;
  for (const auto since = Clock::now();;) {
    take_status();
    check_exits(false);
    if (!out_.reason.empty()) return false;
    const std::string late = hooks_.unmatched_readers(watch_);
    if (late.empty()) return true;
    if (seconds_since(since) > 10.0) {
      const std::string why = "the nodes' writers did not match every reader on the domain within 10 s: " + late +
                              "; a recorder may miss the first steps";
      say("warning: " + why);
      warnings_.push_back(why);
      return true;
    }
    if (hooks_.interrupted && hooks_.interrupted()) return true;
    participant_.wait(std::chrono::milliseconds(2));
  }
}

// The passes of a run: start every node, send the start command once all are ready and
// matched, supervise until the run ends, then conclude (stop what is left on a failure).
SupervisedRun Supervisor::run() {
  for (const auto& node : nodes_) watch_[node] = {};
  for (NodeHost* host : hosts_) host->start_all();
  if (wait_ready() && wait_readers()) {
    send_start();
    supervise();
    out_.wall_time_s = since_start();
  }
  conclude();
  return out_;
}

void Supervisor::send_start() {
  start_ = opt_.start;
  // Real-time pacing counts from the start command: step 0 is due a moment after it is
  // sent, so that every node has it by then.
  if (start_.mode == transport::RunMode::realtime) start_.start_wall_ns = Pacer::now_ns() + 50'000'000;
  control_.write(start_);
  started_ = Clock::now();
  for (auto& [name, w] : watch_) w.last_seen = started_;
}

void Supervisor::note_done_times() {
  for (auto& [name, w] : watch_)
    if (w.last.state == transport::NodeState::done && w.done_at_s < 0) w.done_at_s = since_start();
}

void Supervisor::note_stepping_after_rollback() {
  // The run steps again once every node is past the checkpoint it went back to.
  if (restart_log_.empty() || restart_log_.back().stepping_s >= 0 || restart_log_.back().resumed_s < 0) return;
  bool past = true;
  for (const auto& [name, w] : watch_)
    past = past && w.last.state != transport::NodeState::ready && w.last.header.step > restart_log_.back().rollback_step;
  if (past)
    for (auto& r : restart_log_)
      if (r.generation == restart_log_.back().generation) r.stepping_s = since_start();
}

bool Supervisor::finish_if_all_exited() {
  bool all_exited = true;
  for (const auto& node : nodes_) all_exited = all_exited && host_of(node).exited(node);
  if (!all_exited) return false;
  out_.ok = true;
  // The final statuses (done, with the solver statistics) may still be in flight.
  for (int i = 0; i < 20; ++i) {
    take_status();
    bool all = true;
    for (const auto& [name, w] : watch_) all = all && w.last.state == transport::NodeState::done;
    if (all) break;
    participant_.wait(std::chrono::milliseconds(5));
  }
  note_done_times();
  return true;
}

void Supervisor::supervise() {
  auto last_progress = Clock::now();
  for (;;) {
    take_status();
    note_done_times();
    check_exits(true);
    if (!out_.reason.empty()) break;
    if (!to_restart_.empty()) {
      roll_back();
      if (!out_.reason.empty()) break;
      if (hooks_.interrupted && hooks_.interrupted()) continue;
    }
    note_stepping_after_rollback();
    if (finish_if_all_exited()) break;
    if (const int sig = hooks_.interrupted ? hooks_.interrupted() : 0) {
      fail("", "interrupted by signal " + std::to_string(sig));
      out_.exit_code = 130;
      break;
    }
    watch_silence();
    if (!out_.reason.empty()) break;
    if (hooks_.progress && seconds_since(last_progress) > 0.2) {
      hooks_.progress(watch_, since_start(), false);
      last_progress = Clock::now();
    }
    participant_.wait(std::chrono::milliseconds(20));
  }
}

void Supervisor::conclude() {
  double done_max = 0;
  bool all_done = true;
  for (const auto& [name, w] : watch_) {
    all_done = all_done && w.done_at_s >= 0;
    done_max = std::max(done_max, w.done_at_s);
  }
  if (out_.ok && all_done) out_.wall_time_s = done_max;  // excludes process tear-down
  if (out_.ok) {
    if (hooks_.progress) hooks_.progress(watch_, out_.wall_time_s, true);
  } else {
    // Tell the others, then make sure: every node stops, none is left behind.
    transport::ControlMessage abort = opt_.start;
    abort.command = transport::ControlCommand::abort;
    control_.write(abort);
    for (NodeHost* host : hosts_) host->request_stop();
    for (NodeHost* host : hosts_) host->stop_all(2.0);
  }
}

}  // namespace mechsim::cosim

#include "mechsim/cosim/thread_host.h"

#include <set>
#include <stdexcept>

#include "mechsim/cosim/step_topic.h"

namespace mechsim::cosim {

namespace {

// Every data topic the nodes of this executor write: read from memory by the others.
std::set<std::string> topics_written_by(const std::vector<std::string>& names, const std::vector<const ScenePlan*>& plans) {
  std::set<std::string> topics;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const PlannedNode& node = plans[i]->node(names[i]);
    topics.insert(node.topic);
    if (node.cut) topics.insert(node.cut->topic);
    if (plans[i]->grid()->is_adaptive()) topics.insert(step_topic(names[i]));
  }
  return topics;
}

// Some input of the node (a partner's state or prediction, a step proposal) comes from a
// participant outside this executor: when it is idle, it waits on its participant.
bool reads_from_outside(const ScenePlan& plan, const std::string& name, const std::set<std::string>& members) {
  const PlannedNode& node = plan.node(name);
  for (const auto& edge : node.inputs)
    if (!members.count(edge.from)) return true;
  if (node.cut && !members.count(node.cut->partner)) return true;
  if (plan.grid()->is_adaptive())
    for (const auto& other : plan.nodes())
      if (!members.count(other.name())) return true;
  return false;
}

// With several nodes waiting on their own participants, the executor waits on one of them
// at a time, at most this long, so that a sample for another is taken soon after it came.
constexpr std::chrono::nanoseconds kShareWait{200'000};

}  // namespace

ThreadNodeHost::ThreadNodeHost(std::vector<std::string> nodes, MakeParts make_parts, NodeRunOptions options)
    : names_(std::move(nodes)), make_parts_(std::move(make_parts)), options_(std::move(options)) {
  options_.stop_requested = &stop_;
}

ThreadNodeHost::~ThreadNodeHost() {
  request_stop();
  stop_all(0);
}

void ThreadNodeHost::start_all() {
  std::vector<const ScenePlan*> plans;
  for (const auto& name : names_) {
    auto slot = std::make_unique<Slot>();
    slot->name = name;
    slot->parts = make_parts_(name);
    slot->options = slot->parts.options.value_or(options_);
    slot->options.stop_requested = &stop_;
    plans.push_back(slot->parts.plan.get());
    slots_.push_back(std::move(slot));
  }
  handoff_ = std::make_unique<transport::LocalHandoff>(topics_written_by(names_, plans));
  const std::set<std::string> members(names_.begin(), names_.end());
  for (auto& slot : slots_) {
    slot->parts.participant = handoff_->member(std::move(slot->parts.participant));
    slot->external = reads_from_outside(*slot->parts.plan, slot->name, members);
  }
  executor_ = std::thread([this] { execute(); });
}

// The executor: every node's pass in turn, as long as any of them got on; when none did,
// a wait on the participant of a node that waits for samples from outside (or a nap).
void ThreadNodeHost::execute() {
  std::vector<std::unique_ptr<NodeRun>> runs;
  for (auto& slot : slots_)
    runs.push_back(std::make_unique<NodeRun>(*slot->parts.plan, slot->name, *slot->parts.participant, slot->options));
  std::size_t turn = 0;  // which of several outside-waiting nodes is waited on next
  std::vector<std::size_t> live, outside;  // of this pass; kept, so that a pass allocates nothing
  live.reserve(slots_.size());
  outside.reserve(slots_.size());
  for (;;) {
    bool progressed = false;
    live.clear();
    outside.clear();
    for (std::size_t i = 0; i < slots_.size(); ++i) {
      Slot& slot = *slots_[i];
      if (slot.exit_code >= 0) continue;
      const NodeRun::Pass pass = runs[i]->advance();
      if (pass == NodeRun::Pass::ended) {
        ended(slot, runs[i]->exit_code());
        continue;
      }
      progressed |= pass == NodeRun::Pass::progressed;
      live.push_back(i);
      if (slot.external && runs[i]->running()) outside.push_back(i);
    }
    if (live.empty()) break;
    if (progressed) continue;
    if (outside.empty()) {
      runs[live.front()]->wait(std::chrono::nanoseconds::max());
    } else if (outside.size() == 1) {
      runs[outside.front()]->wait(std::chrono::nanoseconds::max());
    } else {
      runs[outside[turn++ % outside.size()]]->wait(kShareWait);
    }
  }
}

void ThreadNodeHost::ended(Slot& slot, int code) {
  {
    std::lock_guard lock(exited_mutex_);
    slot.exit_code = code;
  }
  exited_.notify_all();
}

std::vector<NodeExit> ThreadNodeHost::poll() {
  std::vector<NodeExit> out;
  for (auto& slot : slots_)
    if (!slot->reported && slot->exit_code >= 0) {
      slot->reported = true;
      out.push_back(node_exit(slot->name, slot->exit_code, false));
    }
  return out;
}

const ThreadNodeHost::Slot& ThreadNodeHost::slot(const std::string& node) const {
  for (const auto& s : slots_)
    if (s->name == node) return *s;
  throw std::logic_error("no node named '" + node + "' on this executor");
}

bool ThreadNodeHost::exited(const std::string& node) const { return slot(node).exit_code >= 0; }

int ThreadNodeHost::exit_code(const std::string& node) const { return slot(node).exit_code; }

std::string ThreadNodeHost::describe_exit(const std::string& node) const {
  const int code = slot(node).exit_code;
  if (code < 0) return "running";
  if (code == node_exit_code::done) return "done";
  if (code == node_exit_code::failed) return "failed";
  if (code == node_exit_code::diverged) return "failed (diverged)";
  return "stopped (exit code " + std::to_string(code) + ")";
}

void ThreadNodeHost::request_stop() {
  stop_ = true;
  for (auto& slot : slots_) slot->parts.participant->wake();
}

void ThreadNodeHost::stop_all(double) {
  if (executor_.joinable()) executor_.join();
}

void ThreadNodeHost::wait_for_exit(std::chrono::milliseconds timeout) {
  std::unique_lock lock(exited_mutex_);
  exited_.wait_for(lock, timeout, [&] {
    for (auto& slot : slots_)
      if (!slot->reported && slot->exit_code >= 0) return true;
    return false;
  });
}

}  // namespace mechsim::cosim

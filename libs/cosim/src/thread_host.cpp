#include "mechsim/cosim/thread_host.h"

#include <stdexcept>

namespace mechsim::cosim {

namespace {

// Cyclone DDS 0.10 crashes when two participants of one process create topics from two
// threads at the same time (measured): every endpoint of the node threads is created under
// one lock. Only creation is serialised; samples flow as before.
std::mutex g_create_mutex;

class SerialisedParticipant : public transport::Participant {
 public:
  explicit SerialisedParticipant(std::unique_ptr<transport::Participant> inner) : inner_(std::move(inner)) {}
  std::unique_ptr<transport::SampleWriter> create_writer(const std::string& topic, const transport::TopicType& type) override {
    std::lock_guard lock(g_create_mutex);
    return inner_->create_writer(topic, type);
  }
  std::unique_ptr<transport::SampleReader> create_reader(const std::string& topic, const transport::TopicType& type) override {
    std::lock_guard lock(g_create_mutex);
    return inner_->create_reader(topic, type);
  }
  std::unique_ptr<transport::SampleWriter> create_redundant_writer(const std::string& topic, const transport::TopicType& type) override {
    std::lock_guard lock(g_create_mutex);
    return inner_->create_redundant_writer(topic, type);
  }
  std::unique_ptr<transport::SampleReader> create_redundant_reader(const std::string& topic, const transport::TopicType& type) override {
    std::lock_guard lock(g_create_mutex);
    return inner_->create_redundant_reader(topic, type);
  }
  std::unique_ptr<transport::ControlWriter> create_control_writer() override {
    std::lock_guard lock(g_create_mutex);
    return inner_->create_control_writer();
  }
  std::unique_ptr<transport::ControlReader> create_control_reader() override {
    std::lock_guard lock(g_create_mutex);
    return inner_->create_control_reader();
  }
  std::unique_ptr<transport::StatusWriter> create_status_writer() override {
    std::lock_guard lock(g_create_mutex);
    return inner_->create_status_writer();
  }
  std::unique_ptr<transport::StatusReader> create_status_reader() override {
    std::lock_guard lock(g_create_mutex);
    return inner_->create_status_reader();
  }
  std::unique_ptr<transport::AgentWriter> create_agent_writer(const std::string& topic) override {
    std::lock_guard lock(g_create_mutex);
    return inner_->create_agent_writer(topic);
  }
  std::unique_ptr<transport::AgentReader> create_agent_reader(const std::string& topic) override {
    std::lock_guard lock(g_create_mutex);
    return inner_->create_agent_reader(topic);
  }
  bool wait(std::chrono::nanoseconds timeout) override { return inner_->wait(timeout); }
  void wake() override { inner_->wake(); }
  std::string vendor() const override { return inner_->vendor(); }

 private:
  std::unique_ptr<transport::Participant> inner_;
};

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
  for (const auto& name : names_) {
    auto slot = std::make_unique<Slot>();
    slot->name = name;
    slot->parts = make_parts_(name);
    slot->parts.participant = std::make_unique<SerialisedParticipant>(std::move(slot->parts.participant));
    slots_.push_back(std::move(slot));
  }
  for (auto& s : slots_) {
    Slot* slot = s.get();
    slot->thread = std::thread([this, slot] {
      int code = 1;
      try {
        NodeRunOptions options = slot->parts.options.value_or(options_);
        options.stop_requested = &stop_;
        code = run_node(*slot->parts.plan, slot->name, *slot->parts.participant, options);
      } catch (const std::exception&) {
        code = 1;  // run_node reports its own errors; this is only a last resort
      }
      {
        std::lock_guard lock(exited_mutex_);
        slot->exit_code = code;
      }
      exited_.notify_all();
    });
  }
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
  throw std::logic_error("no node thread named '" + node + "'");
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
  for (auto& slot : slots_)
    if (slot->thread.joinable()) slot->thread.join();
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

#include "node_status.h"

#include "mechsim/cosim/checkpoint.h"

namespace mechsim::cosim {

using Clock = std::chrono::steady_clock;

NodeStatus::NodeStatus(transport::Participant& participant, std::string node, std::uint64_t run_id,
                       std::int32_t generation, double period_s)
    : writer_(participant.create_status_writer()),
      period_(std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::duration<double>(period_s))),
      started_(Clock::now()) {
  status_.node = std::move(node);
  status_.header.run_id = run_id;
  status_.generation = generation;
}

double NodeStatus::elapsed() const { return std::chrono::duration<double>(Clock::now() - started_).count(); }

void NodeStatus::set_state(transport::NodeState s) {
  status_.state = s;
  send();
}

void NodeStatus::tick() {
  if (Clock::now() >= next_) send();
}

void NodeStatus::send() {
  status_.wall_time = elapsed();
  writer_->write(status_);
  next_ = Clock::now() + period_;
}

std::chrono::nanoseconds NodeStatus::until_next() const {
  const auto d = next_ - Clock::now();
  return d.count() > 0 ? std::chrono::duration_cast<std::chrono::nanoseconds>(d) : std::chrono::nanoseconds(0);
}

void NodeStatus::at_step(std::uint64_t step, double t) {
  status_.header.step = step;
  status_.header.t = t;
}

void NodeStatus::set_readers_matched(int readers) { status_.readers_matched = readers; }

void NodeStatus::rolled_back(std::uint64_t step, std::int32_t generation) {
  status_.rollback_step = static_cast<std::int64_t>(step);
  status_.generation = generation;
  status_.message = rolled_back_message(step, generation);
}

void NodeStatus::resumed() {
  status_.rollback_step = -1;
  status_.message.clear();
}

void NodeStatus::warn(transport::NodeWarning warning, const std::string& text) {
  status_.warning = warning;
  status_.message = text;
}

void NodeStatus::failed(transport::NodeError error, const std::string& text) {
  status_.error = error;
  status_.message = text;
  set_state(transport::NodeState::failed);
}

void NodeStatus::copy_stats(const solve::SolverStats* s) {
  if (!s) return;
  status_.solver_steps = s->steps;
  status_.rhs_evals = s->rhs_evals;
  status_.error_test_failures = s->error_test_failures;
  status_.nonlinear_failures = s->nonlinear_failures;
  status_.roots_found = s->roots_found;
  status_.last_step_size = s->last_step;
  status_.last_order = s->last_order;
}

void NodeStatus::copy_realtime(const RealtimeFigures& f) {
  status_.lateness_max = f.lateness_max;
  status_.lateness_p99 = f.lateness_p99;
  status_.missed_deadlines = f.missed_deadlines;
  status_.rtf_window = f.rtf_window;
}

}  // namespace mechsim::cosim

// The node loop: one short loop over the node's parts (src/node/), each with one job. The
// call order of one step is in docs/node-loop.md.
#include "mechsim/cosim/node_runner.h"

#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>

#include "mechsim/cosim/checkpoint.h"
#include "mechsim/cosim/node_end_record.h"
#include "mechsim/cosim/divergence_guard.h"
#include "mechsim/cosim/node_stepper.h"
#include "mechsim/cosim/step_topic.h"
#include "node/control_inbox.h"
#include "node/node_endpoints.h"
#include "node/node_failure.h"
#include "node/node_pacing.h"
#include "node/node_readiness.h"
#include "node/node_status.h"
#include "node/partition_watch.h"
#include "node/rollback_session.h"
#include "node/sample_gate.h"
#include "node/step_observers.h"

namespace mechsim::cosim {

namespace {

std::vector<std::string> output_names(const PlannedNode& node) {
  std::vector<std::string> names;
  for (const auto& o : node.block->outputs()) names.push_back(o.name);
  return names;
}

bool has_gauss_seidel_input(const PlannedNode& node) {
  for (const auto& edge : node.inputs)
    if (edge.order == config::EdgeOrder::gauss_seidel) return true;
  return false;
}

// Restarted after a crash: the checkpoint to resume from (docs/faults.md).
std::optional<NodeCheckpoint> checkpoint_to_resume(const NodeRunOptions& options, const std::string& node) {
  if (!options.resume_step) return std::nullopt;
  if (options.run_dir.empty()) throw std::runtime_error("--resume needs the run folder (--run-dir)");
  return read_checkpoint(options.run_dir, node, *options.resume_step);
}

}  // namespace

// The loop's parts and its phases (awaiting start, running, awaiting resume, ended); only
// NodeRun drives it. Not in the anonymous namespace: NodeRun::Impl holds one.
class NodeLoop {
 public:
  NodeLoop(ScenePlan& plan, const std::string& name, transport::Participant& participant, const NodeRunOptions& options,
           NodeStatus& status);
  // One pass that never blocks: returns ended with the exit code in exit_code();
  // throws on failure.
  NodeRun::Pass advance();
  void wait(std::chrono::nanoseconds longest);
  bool running() const { return phase_ == Phase::running; }
  // node_exit_code::done or ::stopped.
  int exit_code() const { return exit_code_; }

 private:
  enum class Phase { awaiting_start, running, awaiting_resume, ended };
  void add_observers();
  bool stop_requested() const { return options_.stop_requested && options_.stop_requested->load(); }
  NodeRun::Pass await_start();
  NodeRun::Pass step_while_possible();
  NodeRun::Pass await_resume();
  NodeRun::Pass end(int code);
  void begin_running();
  void initialise();
  void take_step();
  void publish();
  void notify_observers(bool initial);
  void predict_if_due();
  bool take_commands();
  void before_waiting();
  void roll_back(const transport::ControlMessage& command);
  void restore(const NodeCheckpoint& c);
  void go_on_after_rollback();
  NodeCheckpoint checkpoint_now();
  void finish();

  ScenePlan& plan_;
  PlannedNode& node_;
  const config::Scene& scene_;
  const std::string name_;
  transport::Participant& participant_;
  const NodeRunOptions& options_;
  NodeStatus& status_;
  ControlInbox control_;
  NodeEndpoints io_;
  NodeStepper stepper_;
  const std::optional<NodeCheckpoint> resumed_;
  RollbackSession rollback_;
  SampleGate gate_;
  PartitionWatch partition_;
  DivergenceGuard guard_;
  std::vector<std::unique_ptr<StepObserver>> observers_;
  StatusObserver* status_observer_ = nullptr;
  std::optional<NodePacing> pacing_;  // from the start command on
  std::int32_t generation_;
  const bool gauss_seidel_input_;
  bool initialised_ = false;
  Phase phase_ = Phase::awaiting_start;
  int exit_code_ = node_exit_code::stopped;
  std::optional<StartWait> start_wait_;
  std::optional<ResumeWait> resume_wait_;
  transport::SampleHeader header_;
  std::vector<double> values_, prediction_, proposal_fields_;
  std::optional<transport::ControlMessage> pending_rollback_;
};

NodeLoop::NodeLoop(ScenePlan& plan, const std::string& name, transport::Participant& participant,
                   const NodeRunOptions& options, NodeStatus& status)
    : plan_(plan),
      node_(plan.node(name)),
      scene_(plan.scene()),
      name_(name),
      participant_(participant),
      options_(options),
      status_(status),
      control_(participant, options.run_id, options.control_writer, options.domain),
      io_(plan, name, participant, scene_.faults.redundant()),
      stepper_(node_, plan.grid(), plan.nodes().size(), io_.self()),
      resumed_(checkpoint_to_resume(options, name)),
      rollback_(io_, options.lose_first_writes_after_resume, options.lose_write_of_step),
      gate_(plan, node_, io_, stepper_, rollback_, options.run_id, options.domain, resumed_.has_value()),
      partition_(plan, node_, config::fault_timings(scene_).partition_grace),
      guard_(output_names(node_)),
      generation_(options.generation),
      gauss_seidel_input_(has_gauss_seidel_input(node_)),
      header_{options.run_id, 0, scene_.time.start} {
  if (!options_.run_dir.empty()) remove_node_end_record(options_.run_dir, name_);
  add_observers();
  // A resumed node waits for the resume of its generation instead of the start.
  if (resumed_) {
    status_.at_step(resumed_->stepper.step, 0.0);
    status_.rolled_back(resumed_->stepper.step, generation_);
  }
  start_wait_.emplace(io_, control_, status_, resumed_ ? transport::ControlCommand::resume : transport::ControlCommand::start,
                      generation_, options_.start_timeout_s);
}

// In this order: each step's rows, its events, the status, then the checkpoint of them all.
void NodeLoop::add_observers() {
  const std::string& dir = options_.run_dir;
  if (!dir.empty()) {
    const std::string path = dir + "/" + name_ + ".outputs.bin";
    // Paced: the rows go to the disk from a thread of their own (a write can block for ms).
    const auto mode = scene_.mode == config::RunMode::realtime ? OutputLogWriter::Mode::background : OutputLogWriter::Mode::direct;
    observers_.push_back(std::make_unique<OutputLogObserver>(
        resumed_ ? std::make_unique<OutputLogWriter>(path, output_names(node_), OutputLogWriter::Resume{resumed_->output_rows})
                 : std::make_unique<OutputLogWriter>(path, output_names(node_), mode)));
  }
  observers_.push_back(std::make_unique<EventsObserver>(node_, dir.empty() ? "" : dir + "/" + name_ + ".events.jsonl", resumed_.has_value()));
  auto status = std::make_unique<StatusObserver>(status_);
  status_observer_ = status.get();
  observers_.push_back(std::move(status));
  // Restart with rollback: every node checkpoints while some participant may restart.
  if (scene_.checkpointing() && !dir.empty() && scene_.faults.checkpoint_every > 0)
    observers_.push_back(std::make_unique<CheckpointObserver>(
        dir, name_, scene_.faults.checkpoint_every, checkpoints_to_keep(scene_.faults.checkpoint_every, plan_.nodes().size()),
        [this] { return checkpoint_now(); }, options_.checkpoint_pause_step, options_.checkpoint_pause_s));
}

NodeRun::Pass NodeLoop::advance() {
  // A running node takes the steps it can before it looks at a stop (step_while_possible).
  if (phase_ != Phase::ended && phase_ != Phase::running && stop_requested()) return end(node_exit_code::stopped);
  switch (phase_) {
    case Phase::awaiting_start: return await_start();
    case Phase::running: return step_while_possible();
    case Phase::awaiting_resume: return await_resume();
    case Phase::ended: break;
  }
  return NodeRun::Pass::ended;
}

NodeRun::Pass NodeLoop::end(int code) {
  phase_ = Phase::ended;
  exit_code_ = code;
  return NodeRun::Pass::ended;
}

NodeRun::Pass NodeLoop::await_start() {
  switch (start_wait_->poll()) {
    case StartWait::Outcome::waiting: return NodeRun::Pass::idle;
    case StartWait::Outcome::ended: return end(node_exit_code::stopped);
    case StartWait::Outcome::started: break;
  }
  begin_running();
  return NodeRun::Pass::progressed;
}

void NodeLoop::begin_running() {
  status_.resumed();
  status_.set_state(transport::NodeState::running);
  pacing_.emplace(plan_, start_wait_->start());
  start_wait_.reset();
  phase_ = Phase::running;
  if (resumed_) {
    restore(*resumed_);
    std::printf("resumed: from step %llu (generation %d)\n", static_cast<unsigned long long>(header_.step), generation_);
    go_on_after_rollback();
  }
}

// Drain, initialise, step while the inputs allow, then the commands; before an idle pass
// ends, what the node does before it waits (partition watch, resend, heartbeat).
NodeRun::Pass NodeLoop::step_while_possible() {
  bool progressed = false;
  gate_.drain();
  if (!gate_.hold() && !initialised_ && stepper_.can_initialise()) {
    initialise();
    progressed = true;
  }
  predict_if_due();
  while (initialised_ && stepper_.can_step() && !gate_.holding()) {  // a drain below may start a hold
    take_step();
    progressed = true;
    if (stepper_.finished()) break;
    gate_.drain();
    predict_if_due();
    status_.tick();
  }
  if (stepper_.finished()) {
    finish();
    return end(node_exit_code::done);
  }
  if (stop_requested() || take_commands()) return end(node_exit_code::stopped);
  if (pending_rollback_) {
    roll_back(*std::exchange(pending_rollback_, std::nullopt));
    return NodeRun::Pass::progressed;
  }
  if (progressed) return NodeRun::Pass::progressed;
  before_waiting();
  return NodeRun::Pass::idle;
}

NodeRun::Pass NodeLoop::await_resume() {
  switch (resume_wait_->poll()) {
    case ResumeWait::Outcome::waiting: return NodeRun::Pass::idle;
    case ResumeWait::Outcome::ended: return end(node_exit_code::stopped);
    case ResumeWait::Outcome::resumed: break;
  }
  resume_wait_.reset();
  status_.resumed();
  status_.set_state(transport::NodeState::running);
  phase_ = Phase::running;
  go_on_after_rollback();
  return NodeRun::Pass::progressed;
}

void NodeLoop::initialise() {
  stepper_.initialise(values_);
  publish();
  initialised_ = true;
  notify_observers(true);
}

void NodeLoop::take_step() {
  try {
    stepper_.step(values_);
  } catch (const NodeFailure&) {
    throw;
  } catch (const std::exception& e) {
    // A model's own failure (an FMU's step returning an error, a solver giving up): say
    // which step it was, so the run's report names it.
    throw NodeFailure(transport::NodeError::other, "step " + std::to_string(stepper_.step()) + " -> " +
                                                       std::to_string(stepper_.step() + 1) + " (t = " +
                                                       std::to_string(stepper_.time()) + " s): " + e.what());
  }
  publish();
  rollback_.step_taken();
  notify_observers(false);
}

void NodeLoop::publish() {
  if (auto why = guard_.check(stepper_.outputs()))
    throw NodeFailure(transport::NodeError::diverged, "diverged at step " + std::to_string(stepper_.step()) + " (t = " +
                                                          std::to_string(stepper_.time()) + " s): " + *why);
  header_.step = stepper_.step();
  header_.t = stepper_.time();
  pacing_->wait_for_deadline(header_.step);
  rollback_.write_own(header_, values_);
  pacing_->published(header_.step, header_.t, status_);
}

void NodeLoop::notify_observers(bool initial) {
  const CompletedStep s{header_.step, header_.t, stepper_, initial, stepper_.finished()};
  for (auto& o : observers_) o->step_completed(s);
}

// An adaptive step's proposal, then an interface-Jacobian cut's prediction, when due.
void NodeLoop::predict_if_due() {
  if (stepper_.proposal_due()) {
    proposal_to_fields(stepper_.propose(), proposal_fields_);
    io_.write_proposal({options_.run_id, stepper_.step(), stepper_.time()}, proposal_fields_);
  }
  if (!stepper_.prediction_due()) return;
  stepper_.predict(prediction_);
  rollback_.write_prediction({options_.run_id, stepper_.step(), stepper_.time()}, prediction_);
}

// True when the run ends (stop, abort); a rollback is kept for the loop.
bool NodeLoop::take_commands() {
  while (auto c = control_.next()) {
    if (ControlInbox::ends_the_run(*c)) return true;
    if (c->command == transport::ControlCommand::rollback && c->generation > generation_) pending_rollback_ = *c;
  }
  return false;
}

void NodeLoop::before_waiting() {
  if (gate_.holding()) partition_.excuse();  // a hold is not a partition
  partition_.check(stepper_, initialised_, rollback_.within_after_resume(RollbackSession::kForeignWriterGrace));
  rollback_.resend_if_stalled(stepper_.step());
  status_.copy_stats(stepper_.solver_stats());
  pacing_->report(status_);
  status_.tick();
}

void NodeLoop::wait(std::chrono::nanoseconds longest) {
  if (phase_ == Phase::awaiting_start) return std::this_thread::sleep_for(std::min(start_wait_->nap(), longest));
  if (phase_ == Phase::awaiting_resume) return std::this_thread::sleep_for(std::min(resume_wait_->nap(), longest));
  if (phase_ != Phase::running) return;
  // A node with a Gauss-Seidel input waits for its partners' next step (due at the deadline
  // of the step it publishes next); otherwise for samples of the step it has just published.
  const std::uint64_t awaited = stepper_.step() + (initialised_ && gauss_seidel_input_ ? 1 : 0);
  pacing_->wait_for_samples(
      participant_, status_, awaited,
      [this] {
        gate_.drain();
        predict_if_due();
        return initialised_ ? stepper_.can_step() : stepper_.can_initialise();
      },
      longest);
}

// Back to the checkpoint the launcher names, then wait for its resume (docs/faults.md).
void NodeLoop::roll_back(const transport::ControlMessage& command) {
  restore(read_checkpoint(options_.run_dir, name_, command.step));
  generation_ = command.generation;
  std::printf("rollback: to step %llu (generation %d)\n", static_cast<unsigned long long>(command.step), generation_);
  status_.rolled_back(command.step, generation_);
  status_.set_state(transport::NodeState::ready);
  resume_wait_.emplace(control_, status_, generation_);
  phase_ = Phase::awaiting_resume;
}

// Back to a checkpoint's step: the outputs written after it are cut off, so the run folder
// ends as an undisturbed run's.
void NodeLoop::restore(const NodeCheckpoint& c) {
  for (auto& o : observers_) o->restore(c);
  stepper_.restore(c.stepper, values_);
  guard_.restore(c.guard);
  initialised_ = true;
  rollback_.restored(c.stepper.step);
  header_.step = stepper_.step();
  header_.t = stepper_.time();
  status_.at_step(header_.step, header_.t);
}

// The run goes on from the restored step: its samples once more (the partners rolled back
// as well and need them), kept for sending again, and the first step taken reported at once.
void NodeLoop::go_on_after_rollback() {
  rollback_.go_on(header_, values_);
  status_observer_->announce_next_step();
}

NodeCheckpoint NodeLoop::checkpoint_now() {
  NodeCheckpoint c{stepper_.snapshot(), guard_.save(), 0, 0};
  for (auto& o : observers_) o->add_to(c);
  return c;
}

void NodeLoop::finish() {
  for (auto& o : observers_) o->finish();
  if (!options_.run_dir.empty()) pacing_->write_figures(options_.run_dir + "/" + name_ + ".realtime.json");
  io_.flush();
  status_.copy_stats(stepper_.solver_stats());
  // After the logs are flushed: the launcher takes a clean exit without it for an early one.
  if (!options_.run_dir.empty()) write_node_end_record(options_.run_dir, name_, {stepper_.step(), stepper_.time()});
  status_.set_state(transport::NodeState::done);
  std::printf("done: %llu steps, t = %.9g s, %.3f s wall\n", static_cast<unsigned long long>(stepper_.step()), stepper_.time(),
              status_.elapsed());
}

namespace {

int fail(const std::string& node, NodeStatus& status, transport::NodeError error, const char* what, bool lose_status) {
  std::fprintf(stderr, "%s: error: %s\n", node.c_str(), what);
  if (!lose_status) status.failed(error, what);
  return transport::points_to_divergence(error) ? node_exit_code::diverged : node_exit_code::failed;
}

}  // namespace

struct NodeRun::Impl {
  Impl(ScenePlan& plan, const std::string& node_name, transport::Participant& participant, const NodeRunOptions& options)
      : name(node_name), options(options), status(participant, node_name, options.run_id, options.generation, options.heartbeat_s) {
    guarded([&] {
      status.set_state(transport::NodeState::starting);
      loop.emplace(plan, node_name, participant, options, status);
    });
  }
  // Runs `f`; a failure ends the run with its exit code, as a node process that fails.
  template <class F>
  void guarded(F&& f) {
    try {
      f();
      return;
    } catch (const NodeFailure& e) {
      code = fail(name, status, e.kind(), e.what(), options.lose_failed_status);
    } catch (const std::exception& e) {
      code = fail(name, status, transport::NodeError::other, e.what(), options.lose_failed_status);
    }
    loop.reset();
  }

  const std::string name;
  const NodeRunOptions& options;
  NodeStatus status;
  std::optional<NodeLoop> loop;
  std::optional<int> code;  // once ended
};

NodeRun::NodeRun(ScenePlan& plan, const std::string& node_name, transport::Participant& participant, const NodeRunOptions& options)
    : impl_(std::make_unique<Impl>(plan, node_name, participant, options)) {}

NodeRun::~NodeRun() = default;

NodeRun::Pass NodeRun::advance() {
  Impl& r = *impl_;
  if (r.code) return Pass::ended;
  Pass pass = Pass::ended;
  r.guarded([&] {
    pass = r.loop->advance();
    if (pass == Pass::ended) r.code = r.loop->exit_code();
  });
  return r.code ? Pass::ended : pass;
}

void NodeRun::wait(std::chrono::nanoseconds longest) {
  Impl& r = *impl_;
  if (!r.code) r.guarded([&] { r.loop->wait(longest); });
}

bool NodeRun::running() const { return !impl_->code && impl_->loop->running(); }

int NodeRun::exit_code() const { return impl_->code.value_or(node_exit_code::stopped); }

int run_node(ScenePlan& plan, const std::string& node_name, transport::Participant& participant,
             const NodeRunOptions& options) {
  NodeRun run(plan, node_name, participant, options);
  for (;;) {
    const NodeRun::Pass pass = run.advance();
    if (pass == NodeRun::Pass::ended) return run.exit_code();
    if (pass == NodeRun::Pass::idle) run.wait(std::chrono::nanoseconds::max());
  }
}

}  // namespace mechsim::cosim

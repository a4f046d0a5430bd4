#include "mechsim/cosim/node_runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <thread>

#include <sched.h>
#include <unistd.h>
#include <stdexcept>

#include "mechsim/cosim/checkpoint.h"
#include "mechsim/cosim/divergence_guard.h"
#include "mechsim/cosim/node_stepper.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/pacer.h"
#include "mechsim/cosim/step_topic.h"

namespace mechsim::cosim {

namespace {

using Clock = std::chrono::steady_clock;

class Heartbeat {
 public:
  Heartbeat(transport::StatusWriter& writer, std::string node, std::uint64_t run_id, double period_s)
      : writer_(writer), period_(period_s), started_(Clock::now()) {
    status_.node = std::move(node);
    status_.header.run_id = run_id;
  }
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - started_).count(); }
  transport::StatusMessage& status() { return status_; }
  void set_state(transport::NodeState s) {
    status_.state = s;
    send();
  }
  // Sends when the period has passed since the last one.
  void tick() {
    if (Clock::now() >= next_) send();
  }
  void send() {
    status_.wall_time = elapsed();
    writer_.write(status_);
    next_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period_));
  }
  std::chrono::nanoseconds until_next() const {
    auto d = next_ - Clock::now();
    return d.count() > 0 ? std::chrono::duration_cast<std::chrono::nanoseconds>(d) : std::chrono::nanoseconds(0);
  }

 private:
  transport::StatusWriter& writer_;
  double period_;
  Clock::time_point started_;
  Clock::time_point next_{};
  transport::StatusMessage status_;
};

void copy_stats(const solve::SolverStats* s, transport::StatusMessage& m) {
  if (!s) return;
  m.solver_steps = s->steps;
  m.rhs_evals = s->rhs_evals;
  m.error_test_failures = s->error_test_failures;
  m.nonlinear_failures = s->nonlinear_failures;
  m.roots_found = s->roots_found;
  m.last_step_size = s->last_step;
  m.last_order = s->last_order;
}

// One JSON line per event, and a line in the node's log.
void log_event(const models::BlockEvent& ev, const std::unique_ptr<std::FILE, int (*)(std::FILE*)>& file) {
  std::string line = "{\"kind\": \"" + ev.kind + "\", \"t_s\": " + std::to_string(ev.t);
  char buf[64];
  for (const auto& [name, value] : ev.values) {
    std::snprintf(buf, sizeof buf, "%.17g", value);
    line += ", \"" + name + "\": " + (std::isfinite(value) ? std::string(buf) : std::string("null"));
  }
  line += "}";
  std::printf("event: %s\n", line.c_str());
  if (file) {
    std::fprintf(file.get(), "%s\n", line.c_str());
    std::fflush(file.get());
  }
}

// Cuts a stdio file to `bytes` and goes on writing at its end (a rollback of the events file).
void truncate_stdio(std::FILE* f, std::int64_t bytes, const std::string& what) {
  std::fflush(f);
  if (::ftruncate(::fileno(f), bytes) != 0 || std::fseek(f, bytes, SEEK_SET) != 0)
    throw std::runtime_error(what + ": cannot truncate to the checkpoint");
}

// The node's real-time figures and its lateness histogram (non-empty 1 us bins as
// [bin, count] pairs) for the launcher's summary and the lateness PNG.
void write_realtime_figures(const std::string& path, const Pacer& pacer) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (!out) return;
  const RealtimeFigures f = pacer.figures();
  const LatenessHistogram& h = pacer.histogram();
  std::fprintf(out,
               "{\"publications\": %ld, \"missed_deadlines\": %ld, \"lateness_median_s\": %.9g, "
               "\"lateness_p99_s\": %.9g, \"lateness_max_s\": %.9g, \"rtf_achieved\": %.6g, \"rtf_window\": %.6g, "
               "\"paced_wall_time_s\": %.9g, \"period_jitter_std_s\": %.9g, \"period_jitter_max_s\": %.9g,\n"
               " \"lateness_histogram\": {\"bin_s\": %g, \"overflow\": %ld, \"bins\": [",
               f.publications, f.missed_deadlines, f.lateness_median, f.lateness_p99, f.lateness_max, f.rtf_achieved,
               f.rtf_window, f.paced_wall_time, f.period_jitter_std, f.period_jitter_max, LatenessHistogram::kBinWidth,
               h.overflow());
  bool first = true;
  for (std::size_t b = 0; b < h.counts().size(); ++b)
    if (h.counts()[b]) {
      std::fprintf(out, "%s[%zu, %u]", first ? "" : ", ", b, h.counts()[b]);
      first = false;
    }
  std::fprintf(out, "]},\n \"worst\": [");
  first = true;
  for (const Pacer::Late& l : pacer.worst()) {
    std::fprintf(out, "%s{\"step\": %llu, \"lateness_s\": %.9g}", first ? "" : ", ", static_cast<unsigned long long>(l.step), l.lateness);
    first = false;
  }
  std::fprintf(out, "]}\n");
  std::fclose(out);
}

// "participant 'slide' (topic slide/state) on host c (10.77.0.3)" for failure messages.
std::string describe_partner(const config::Scene& scene, const std::string& participant, const std::string& topic) {
  std::string out = "participant '" + participant + "' (topic " + topic + ")";
  const config::ParticipantSpec* p = scene.find_participant(participant);
  if (p && !p->host.empty())
    if (const config::HostSpec* h = scene.find_host(p->host)) out += " on host " + h->name + " (" + h->address + ")";
  return out;
}

}  // namespace

int run_node(ScenePlan& plan, const std::string& node_name, transport::Participant& participant,
             const NodeRunOptions& options) {
  PlannedNode& node = plan.node(node_name);
  const config::Scene& scene = plan.scene();
  auto status_writer = participant.create_status_writer();
  Heartbeat beat(*status_writer, node_name, options.run_id, options.heartbeat_s);
  auto stop_requested = [&] { return options.stop_requested && options.stop_requested->load(); };

  try {
    beat.set_state(transport::NodeState::starting);
    auto control = participant.create_control_reader();
    // mechsim/control has one writer, the launcher, whose GUID the node got on its command
    // line. A command of another run (a reused domain's stale sample) is ignored; a command
    // of this run from any other writer is an intruder's: start, stop or abort alike.
    auto command_for_this_run = [&](const transport::ControlMessage& c) {
      if (c.run_id != options.run_id) return false;
      if (!options.control_writer.empty() && c.writer != options.control_writer) {
        std::string ids;
        for (const auto& id : control->matched_writer_ids()) ids += (ids.empty() ? "" : "; ") + id;
        throw std::runtime_error("foreign data on topic 'mechsim/control' (the scene's only writer is the launcher, GUID " +
                                 options.control_writer + "): command " + std::to_string(static_cast<int>(c.command)) +
                                 " for this run from writer " + (c.writer.empty() ? std::string("(unknown)") : c.writer) +
                                 (ids.empty() ? "" : "; matched writers: " + ids) +
                                 "; a participant that does not belong to this run writes into its domain " +
                                 std::to_string(options.domain) + " (docs/faults.md)");
      }
      return true;
    };
    // The next command of this run (nullopt: none waiting), and whether it ends the run.
    auto next_command = [&]() -> std::optional<transport::ControlMessage> {
      while (auto c = control->take())
        if (command_for_this_run(*c)) return c;
      return std::nullopt;
    };
    auto ends_the_run = [](const transport::ControlMessage& c) {
      return c.command == transport::ControlCommand::abort || c.command == transport::ControlCommand::stop;
    };
    auto writer = participant.create_writer(node.topic, *node.type->publishes);
    std::vector<std::unique_ptr<transport::SampleReader>> readers;
    for (const auto& edge : node.inputs) readers.push_back(participant.create_reader(edge.topic, *edge.type));
    // Interface-Jacobian cut: this side's predictions out, the partner's in.
    std::unique_ptr<transport::SampleWriter> cut_writer;
    std::unique_ptr<transport::SampleReader> cut_reader;
    if (node.cut) {
      cut_writer = participant.create_writer(node.cut->topic, *node.cut->type);
      cut_reader = participant.create_reader(node.cut->partner_topic, *node.cut->type);
    }
    // Redundant samples (docs/faults.md): every sample also on the best-effort twin topic;
    // whichever copy of a step arrives first is used, the other is a duplicate the input
    // channels drop. Not part of readiness: a twin that loses its first samples costs nothing.
    std::unique_ptr<transport::SampleWriter> twin_writer, twin_cut_writer;
    std::vector<std::unique_ptr<transport::SampleReader>> twin_readers;
    std::unique_ptr<transport::SampleReader> twin_cut_reader;
    if (scene.faults.redundant()) {
      twin_writer = participant.create_redundant_writer(node.topic, *node.type->publishes);
      for (const auto& edge : node.inputs) twin_readers.push_back(participant.create_redundant_reader(edge.topic, *edge.type));
      if (node.cut) {
        twin_cut_writer = participant.create_redundant_writer(node.cut->topic, *node.cut->type);
        twin_cut_reader = participant.create_redundant_reader(node.cut->partner_topic, *node.cut->type);
      }
    }

    // Adaptive macro step: this node's proposals out, every other participant's in
    // (step_control.h; the proposals of one step agree in every node without the launcher).
    const bool adaptive = plan.grid()->is_adaptive();
    std::size_t self = 0;
    while (plan.nodes()[self].name() != node_name) ++self;
    std::unique_ptr<transport::SampleWriter> step_writer;
    struct ProposalReader {
      std::size_t participant;
      std::string topic;
      std::unique_ptr<transport::SampleReader> reader;
    };
    std::vector<ProposalReader> step_readers;
    if (adaptive) {
      const transport::TopicType& type = step_proposal_type();
      step_writer = participant.create_writer(step_topic(node_name), type);
      for (std::size_t i = 0; i < plan.nodes().size(); ++i)
        if (i != self) {
          const std::string topic = step_topic(plan.nodes()[i].name());
          step_readers.push_back({i, topic, participant.create_reader(topic, type)});
        }
    }
    NodeStepper stepper(node, plan.grid(), plan.nodes().size(), self);
    // Restarted after a crash: the checkpoint to resume from (docs/faults.md).
    std::optional<NodeCheckpoint> resumed;
    if (options.resume_step) {
      if (options.run_dir.empty()) throw std::runtime_error("--resume needs the run folder (--run-dir)");
      resumed = read_checkpoint(options.run_dir, node_name, *options.resume_step);
    }
    const std::string events_path = options.run_dir + "/" + node_name + ".events.jsonl";
    // Events the block reports (lift-off, landing, ...): JSON lines for the launcher's summary.
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> events_file(nullptr, &std::fclose);
    if (!options.run_dir.empty()) events_file.reset(std::fopen(events_path.c_str(), resumed ? "r+" : "w"));
    if (resumed && events_file) truncate_stdio(events_file.get(), resumed->events_bytes, events_path);
    std::unique_ptr<OutputLogWriter> log;
    if (!options.run_dir.empty()) {
      std::vector<std::string> columns;
      for (const auto& o : node.block->outputs()) columns.push_back(o.name);
      const std::string path = options.run_dir + "/" + node_name + ".outputs.bin";
      // Paced: the rows go to the disk from a thread of their own (a write can block for ms).
      if (resumed)
        log = std::make_unique<OutputLogWriter>(path, columns, OutputLogWriter::Resume{resumed->output_rows});
      else
        log = std::make_unique<OutputLogWriter>(path, columns, scene.mode == "realtime" ? OutputLogWriter::Mode::background
                                                                                      : OutputLogWriter::Mode::direct);
    }
    // Restart with rollback: every node checkpoints while some participant may restart.
    const long checkpoint_every = scene.checkpointing() && !options.run_dir.empty() ? scene.faults.checkpoint_every : 0;
    const int checkpoints_kept = checkpoints_to_keep(scene.faults.checkpoint_every, plan.nodes().size());
    std::int32_t generation = options.generation;

    // Ready means matched both ways with every partner (see docs/protocol.md: a match seen
    // by only one side can lose the first sample), then wait for the start command.
    auto matched = [&] {
      if (writer->matched_readers() < node.subscriber_count) return false;
      if (node.recorded && writer->matched_readers_including_tools() < node.subscriber_count + 1) return false;
      for (const auto& r : readers)
        if (r->matched_writers() < 1) return false;
      if (step_writer && step_writer->matched_readers() < static_cast<int>(step_readers.size())) return false;
      for (const auto& r : step_readers)
        if (r.reader->matched_writers() < 1) return false;
      return !node.cut || (cut_writer->matched_readers() >= 1 && cut_reader->matched_writers() >= 1);
    };
    bool ready = false, started = false;
    transport::ControlMessage start_message;
    // A resumed node waits for the resume of its generation instead of the start.
    const auto awaited = resumed ? transport::ControlCommand::resume : transport::ControlCommand::start;
    if (resumed) {
      beat.status().header.step = resumed->stepper.step;
      beat.status().message = rolled_back_message(resumed->stepper.step, generation);
    }
    const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                             std::chrono::duration<double>(options.start_timeout_s));
    while (!started) {
      if (stop_requested()) return 3;
      if (Clock::now() > deadline) throw std::runtime_error("no start command within the start timeout");
      // For the launcher: it starts the run once every reader on the domain, a recorder of
      // the user's included, is matched with this writer (docs/recording.md).
      beat.status().readers_matched = writer->matched_readers_including_tools();
      if (!ready && matched()) {
        ready = true;
        beat.set_state(transport::NodeState::ready);
      }
      while (auto c = next_command()) {
        if (ends_the_run(*c)) return 3;
        if (c->command != awaited || c->generation != generation) continue;  // e.g. the rollback a resumed node is part of
        started = ready;
        start_message = *c;
        if (!ready) throw std::runtime_error("start command before this node was matched with its partners");
      }
      beat.tick();
      // Not the waitset: a partner that started first may already have sent its step 0,
      // which this loop does not take, so the waitset would return at once and this thread
      // would spin; under SCHED_FIFO on a pinned CPU that spin starves the node's own DDS
      // receive thread, which would deliver the start command (a livelock, seen here). A
      // 1 ms sleep is early enough: step 0 is due 50 ms after the start command.
      if (!started) std::this_thread::sleep_for(std::min(beat.until_next(), std::chrono::nanoseconds(1'000'000)));
    }
    beat.status().message.clear();
    beat.set_state(transport::NodeState::running);

    transport::SampleHeader header{options.run_id, 0, scene.time.start};
    std::vector<double> values, received;
    // Nobody else writes into the run (docs/faults.md, 'Foreign writers'): each input topic
    // has exactly the one writer the scene plans, its samples come one step after the other,
    // and the redundant copy of a step carries the same values. Checked whenever samples
    // were taken, before they are used.
    std::vector<std::uint64_t> next_step(readers.size(), 0);
    // A second writer: hold (use no sample) while it lasts; a writer of a process that died
    // lingers until its DDS lease runs out (2 s; a domain is reused by later runs), so only a
    // second writer that stays longer than kForeignWriterGrace is foreign.
    constexpr double kForeignWriterGrace = 4.0;  // s, above the 2 s lease of config/dds/
    // After a rollback's resume (resumed_at; none: never rolled back) the protocol is
    // lenient for a while, each window counted from the resume:
    //  - kForeignWriterGrace: a node that stalls sends again what it wrote since the
    //    rollback (`resend_since_rollback`), and a stall is no partition;
    //  - kLingeringAfterResume, longer, so that a copy sent at the edge is still taken: a
    //    step from the rollback's step K up to the newest one seen is a repeat (checked for
    //    equal values where still in use), and a restarted partner's dead writer may
    //    linger beside its new one (it took more than 4 s under load once).
    constexpr double kLingeringAfterResume = 10.0;  // s
    std::optional<Clock::time_point> resumed_at;
    auto within_after_resume = [&](double seconds) {
      return resumed_at && Clock::now() - *resumed_at < std::chrono::duration<double>(seconds);
    };
    // Otherwise a stream must go on one step after the other. A resumed node takes up a
    // stream wherever it is.
    std::vector<bool> next_step_known(readers.size(), !resumed);
    std::optional<std::uint64_t> rollback_step;
    if (resumed) rollback_step = resumed->stepper.step;
    auto in_sequence = [&](std::size_t e, std::uint64_t step) {
      if (!next_step_known[e] || step == next_step[e]) return true;
      return rollback_step && step >= *rollback_step && step < next_step[e] && within_after_resume(kLingeringAfterResume);
    };
    // The message names the writers the reader is matched with: the intruder among them.
    auto foreign = [&](const transport::SampleReader* r, const std::string& topic, const std::string& from, const std::string& what) {
      std::string ids;
      for (const auto& id : r->matched_writer_ids()) ids += (ids.empty() ? "" : "; ") + id;
      throw std::runtime_error("foreign data on topic '" + topic + "' (the scene's only writer is participant '" + from + "'): " + what +
                               "; " + std::to_string(r->matched_writers()) + " writer(s) matched" + (ids.empty() ? "" : " (" + ids + ")") +
                               "; a participant that does not belong to this run writes into its domain " +
                               std::to_string(options.domain) + " (docs/faults.md)");
    };
    std::optional<Clock::time_point> second_writer_since;
    // Every reader of a partner's samples, with the topic and the participant it expects.
    struct WatchedReader {
      const transport::SampleReader* reader;
      std::string topic, from;
    };
    std::vector<WatchedReader> watched;
    for (std::size_t e = 0; e < readers.size(); ++e) {
      watched.push_back({readers[e].get(), node.inputs[e].topic, node.inputs[e].from});
      if (e < twin_readers.size() && twin_readers[e]) watched.push_back({twin_readers[e].get(), transport::redundant_topic(node.inputs[e].topic), node.inputs[e].from});
    }
    if (cut_reader) watched.push_back({cut_reader.get(), node.cut->partner_topic, node.cut->partner});
    if (twin_cut_reader) watched.push_back({twin_cut_reader.get(), transport::redundant_topic(node.cut->partner_topic), node.cut->partner});
    // No hold (and no failure) for a second writer while a restarted partner's dead one may
    // still linger; after that a second writer is one like any other.
    auto holding = [&] { return second_writer_since.has_value() && !within_after_resume(kLingeringAfterResume); };
    // True while the node must hold; throws once a second writer outstayed the grace.
    auto hold_for_second_writer = [&] {
      const auto w = std::find_if(watched.begin(), watched.end(), [](const WatchedReader& r) { return r.reader->matched_writers() > 1; });
      if (w == watched.end()) {
        second_writer_since.reset();
        return false;
      }
      if (!second_writer_since) second_writer_since = Clock::now();
      if (std::chrono::duration<double>(Clock::now() - *second_writer_since).count() > kForeignWriterGrace &&
          !within_after_resume(kLingeringAfterResume))
        foreign(w->reader, w->topic, w->from, "more than one writer for " + std::to_string(static_cast<int>(kForeignWriterGrace)) + " s");
      return holding();
    };
    // Fields the publisher does not compute are NaN by design (PlannedNode::published_outputs).
    std::vector<std::vector<int>> checked_fields(node.inputs.size());
    for (std::size_t e = 0; e < node.inputs.size(); ++e) {
      const PlannedNode& publisher = plan.node(node.inputs[e].from);
      for (const auto& [field, input] : node.inputs[e].field_to_input)
        if (field < static_cast<int>(publisher.published_outputs.size()) && publisher.published_outputs[static_cast<std::size_t>(field)] >= 0)
          checked_fields[e].push_back(field);
    }
    auto check_plausible = [&](std::size_t e, const transport::SampleHeader& h, const std::vector<double>& v) {
      const InboundEdge& edge = node.inputs[e];
      for (const int field : checked_fields[e]) {
        const transport::FieldInfo& f = edge.type->fields[static_cast<std::size_t>(field)];
        const double x = v[static_cast<std::size_t>(field)];
        if (std::isfinite(x) && x >= f.min && x <= f.max) continue;
        char buf[160];
        std::snprintf(buf, sizeof buf, "%s = %.6g%s%s outside [%g, %g]", f.name.c_str(), x, f.unit.empty() ? "" : " ", f.unit.c_str(), f.min, f.max);
        // With a second writer matched the sample is most likely not the partner's at all.
        if (readers[e]->matched_writers() > 1)
          foreign(readers[e].get(), edge.topic, edge.from, std::string("an implausible sample for step ") + std::to_string(h.step) + " (" + buf + ")");
        // From the partner itself: it diverged (its own guard had not caught it yet) or its
        // data is corrupted; "diverged" makes the launcher look for a stable macro step.
        throw std::runtime_error("implausible sample on topic '" + edge.topic + "' from participant '" + edge.from + "', step " +
                                 std::to_string(h.step) + ": " + buf + " (bounds: docs/dds.md, 'Plausible samples'): participant '" +
                                 edge.from + "' diverged, or its data is corrupted");
      }
    };
    auto drain = [&] {
      bool took = false;
      for (std::size_t e = 0; e < readers.size(); ++e) {
        const InboundEdge& edge = node.inputs[e];
        transport::SampleHeader h;
        while (readers[e]->take(h, received)) {
          took = true;
          if (h.run_id != options.run_id) continue;
          if (!in_sequence(e, h.step)) {
            // A step ahead of the one due, from the one writer the plan expects: the DDS
            // layer skipped a sample of its reliable stream (seen under 5 % loss between
            // Fast DDS and Cyclone at the start of a run); the step due comes from the
            // redundant copy or the run stalls and ends at the partition grace. Anything
            // else out of order is foreign.
            if (!(h.step > next_step[e] && readers[e]->matched_writers() == 1))
              foreign(readers[e].get(), edge.topic, edge.from, "step " + std::to_string(h.step) + " arrived where step " + std::to_string(next_step[e]) + " was due");
            std::printf("warning: topic '%s': step %llu arrived where step %llu was due (one writer matched): the reliable stream skipped; taking it\n",
                        edge.topic.c_str(), static_cast<unsigned long long>(h.step), static_cast<unsigned long long>(next_step[e]));
          }
          next_step[e] = next_step_known[e] ? std::max(next_step[e], h.step + 1) : h.step + 1;
          next_step_known[e] = true;
          check_plausible(e, h, received);
          if (h.step + 2 >= stepper.step() && !stepper.channel(e).add(h.step, received))
            foreign(readers[e].get(), edge.topic, edge.from, "two different samples for step " + std::to_string(h.step));
        }
        // The twin copy: a step already there (or consumed) is dropped as a duplicate.
        while (e < twin_readers.size() && twin_readers[e] && twin_readers[e]->take(h, received)) {
          took = true;
          if (h.run_id != options.run_id || h.step < stepper.step()) continue;
          check_plausible(e, h, received);
          if (!stepper.channel(e).add(h.step, received))
            foreign(twin_readers[e].get(), transport::redundant_topic(edge.topic), edge.from, "two different samples for step " + std::to_string(h.step));
        }
      }
      transport::SampleHeader h;
      while (cut_reader && cut_reader->take(h, received)) {
        took = true;
        if (h.run_id == options.run_id) stepper.add_partner_prediction(h.step, received);
      }
      while (twin_cut_reader && twin_cut_reader->take(h, received)) {
        took = true;
        if (h.run_id == options.run_id) stepper.add_partner_prediction(h.step, received);
      }
      for (const auto& r : step_readers)
        while (r.reader->take(h, received)) {
          took = true;
          if (h.run_id != options.run_id) continue;
          const StepProposal p = proposal_from_fields(received);
          if (!(p.step_length > 0) || !std::isfinite(p.step_length))
            foreign(r.reader.get(), r.topic, plan.nodes()[r.participant].name(),
                    "a step proposal of length " + std::to_string(p.step_length) + " s for step " + std::to_string(h.step));
          stepper.add_proposal(r.participant, h.step, p);
        }
      if (took) hold_for_second_writer();
    };
    // Every write of the node's own sample and of its cut prediction, each with its
    // redundant twin.
    auto write_own = [&](const transport::SampleHeader& h, const std::vector<double>& v) {
      writer->write(h, v);
      if (twin_writer) twin_writer->write(h, v);
    };
    auto write_prediction = [&](const transport::SampleHeader& h, const std::vector<double>& v) {
      cut_writer->write(h, v);
      if (twin_cut_writer) twin_cut_writer->write(h, v);
    };
    // --- sending again after a rollback ---
    // A restarted node's writers and readers are new to its partners, and DDS discovery
    // completes on each side on its own: a sample written before the other side matched a
    // writer never arrives (VOLATILE), and lock step would wait for it for good (seen in
    // CI). So for kForeignWriterGrace after the resume a node keeps what it
    // wrote since the rollback and writes it again whenever it has waited
    // kResendAfterStall without taking a step; receivers take the copies as repeats
    // (in_sequence). A lost sample stalls its receiver, and in a loop of partners that
    // stall reaches the sender.
    struct SentSample {
      bool prediction;  // the cut topic, else the node's own topic
      transport::SampleHeader header;
      std::vector<double> values;
    };
    std::vector<SentSample> sent_since_rollback;
    constexpr std::size_t kSentKept = 64;  // the newest; partners in lock step are a step or two apart
    constexpr auto kResendAfterStall = std::chrono::milliseconds(100);
    Clock::time_point last_step_taken = Clock::now(), last_resend{};
    auto keep_sent = [&](bool prediction, const transport::SampleHeader& h, const std::vector<double>& v) {
      if (!within_after_resume(kForeignWriterGrace)) return;  // no clock read in a run without rollback
      if (sent_since_rollback.size() == kSentKept) sent_since_rollback.erase(sent_since_rollback.begin());
      sent_since_rollback.push_back({prediction, h, v});
    };
    auto resend_since_rollback = [&] {
      if (sent_since_rollback.empty() || !within_after_resume(kForeignWriterGrace)) return;
      const auto now = Clock::now();
      if (now - last_step_taken < kResendAfterStall || now - last_resend < kResendAfterStall) return;
      if (last_resend < last_step_taken)  // once per stall in the log
        std::printf("rollback: no step for %.2f s at step %llu: %zu sample(s) sent since the rollback sent again\n",
                    std::chrono::duration<double>(now - last_step_taken).count(), static_cast<unsigned long long>(stepper.step()),
                    sent_since_rollback.size());
      last_resend = now;
      for (const SentSample& s : sent_since_rollback) {
        if (s.prediction) write_prediction(s.header, s.values);
        else write_own(s.header, s.values);
      }
    };
    // Test hook (restart_test): MECHSIM_TEST_LOSE_RESTORED_SAMPLE=NODE makes NODE leave out
    // its first writes after a resume (the restored step's sample and the first prediction),
    // as a partner that had not yet matched its writers would miss them.
    const char* lose_hook = std::getenv("MECHSIM_TEST_LOSE_RESTORED_SAMPLE");
    const bool lose_restored_sample = lose_hook && node_name == lose_hook;
    bool lose_next_prediction = false;
    std::vector<double> prediction;
    std::vector<double> proposal_fields;
    auto propose_if_due = [&] {
      if (!stepper.proposal_due()) return;
      const StepProposal p = stepper.propose();
      proposal_to_fields(p, proposal_fields);
      step_writer->write({options.run_id, stepper.step(), stepper.time()}, proposal_fields);
    };
    auto predict_if_due = [&] {
      propose_if_due();
      if (!stepper.prediction_due()) return;
      stepper.predict(prediction);
      const transport::SampleHeader h{options.run_id, stepper.step(), stepper.time()};
      if (!std::exchange(lose_next_prediction, false)) write_prediction(h, prediction);
      keep_sent(true, h, prediction);
    };
    std::optional<transport::ControlMessage> pending_rollback;
    auto check_control = [&] {
      while (auto c = next_command()) {
        if (ends_the_run(*c)) return true;
        if (c->command == transport::ControlCommand::rollback && c->generation > generation) pending_rollback = *c;
      }
      return false;
    };
    std::vector<std::string> output_names;
    for (const auto& o : node.block->outputs()) output_names.push_back(o.name);
    DivergenceGuard guard(output_names);
    // Real-time mode: publication paced to the wall clock from the start command's t_start.
    std::optional<Pacer> pacer;
    const config::RealtimeSpec& rt = scene.realtime;
    if (scene.mode == "realtime") {
      if (start_message.start_wall_ns == 0) throw std::runtime_error("realtime mode without a start time in the start command");
      pacer.emplace(start_message.start_wall_ns, plan.grid(), scene.rtf);
    }
    bool keep_up_checked = false;
    auto pace = [&](std::uint64_t k) {
      const double late = pacer->published(k);
      const double step_wall = scene.time.step / scene.rtf;
      if (rt.on_overrun == "abort" && late > step_wall) {
        char buf[200];
        std::snprintf(buf, sizeof buf, "fell behind its deadline by %.3f ms at step %llu (t = %.6g s; a step is %.3f ms of wall time)",
                      late * 1e3, static_cast<unsigned long long>(k), stepper.time(), step_wall * 1e3);
        throw std::runtime_error(buf);
      }
      // Within the first second: a run that cannot keep up at all is told so, with the
      // rate it reaches (it runs flat out while it is late). Under `abort` the first missed
      // deadline has already stopped the run above, so this is a warning only.
      if (!keep_up_checked && pacer->elapsed() > 1.0) {
        keep_up_checked = true;
        const RealtimeFigures f = pacer->figures();
        if (f.missed_deadlines * 2 > f.publications) {
          char buf[256];
          std::snprintf(buf, sizeof buf, "cannot keep up with rtf %g: missed %ld of %ld deadlines in the first second; "
                        "measured maximum rtf %.3g (%.0f steps/s)", scene.rtf, f.missed_deadlines, f.publications,
                        f.rtf_achieved, f.rtf_achieved / scene.time.step);
          std::printf("warning: %s\n", buf);
          beat.status().message = buf;
        }
      }
    };
    auto publish = [&] {
      if (auto why = guard.check(stepper.outputs()))
        throw std::runtime_error("diverged at step " + std::to_string(stepper.step()) + " (t = " +
                                 std::to_string(stepper.time()) + " s): " + *why);
      header.step = stepper.step();
      header.t = stepper.time();
      if (pacer) pacer->wait_for_deadline(header.step, rt.spin_wait ? rt.spin_limit : 0.0);
      write_own(header, values);
      keep_sent(false, header, values);
      if (pacer) pace(header.step);
      // An event instant's row is logged when the next step starts (NodeStepper::event_row).
      if (log && !stepper.grid().is_event(header.step)) log->append(header.t, stepper.outputs());
      beat.status().header.step = header.step;
      beat.status().header.t = header.t;
    };

    bool initialised = false;
    // --- restart with rollback (checkpoint.h, docs/faults.md) ---
    bool announce_step = false;  // after a resume: the first step taken goes to the launcher at once
    auto write_node_checkpoint = [&] {
      log->flush();
      std::int64_t events_bytes = 0;
      if (events_file) {
        std::fflush(events_file.get());
        events_bytes = std::ftell(events_file.get());
      }
      write_checkpoint(options.run_dir, node_name, {stepper.snapshot(), guard.save(), log->rows(), events_bytes}, checkpoints_kept);
    };
    // Back to a checkpoint's step: the outputs written after it are cut off, so the run
    // folder ends as an undisturbed run's.
    auto apply_checkpoint = [&](const NodeCheckpoint& c) {
      if (log) log->truncate_rows(c.output_rows);
      if (events_file) truncate_stdio(events_file.get(), c.events_bytes, events_path);
      stepper.restore(c.stepper, values);
      guard.restore(c.guard);
      initialised = true;
      rollback_step = c.stepper.step;
      header.step = stepper.step();
      header.t = stepper.time();
      beat.status().header.step = header.step;
      beat.status().header.t = header.t;
    };
    // The run goes on from the restored step: its samples once more (the partners rolled
    // back as well and need them), kept for sending again, and the first step taken
    // reported at once.
    auto go_on_after_rollback = [&] {
      resumed_at = Clock::now();
      sent_since_rollback.clear();
      last_step_taken = Clock::now();
      lose_next_prediction = lose_restored_sample && cut_writer;
      if (!lose_restored_sample) write_own(header, values);
      keep_sent(false, header, values);
      announce_step = true;
    };
    // Waits (heartbeats only, no sample taken) for the resume of `generation`; false when
    // the run is stopped meanwhile.
    auto await_resume = [&] {
      for (;;) {
        if (stop_requested()) return false;
        while (auto c = next_command()) {
          if (ends_the_run(*c)) return false;
          if (c->command == transport::ControlCommand::resume && c->generation == generation) return true;
          if (c->command == transport::ControlCommand::rollback && c->generation > generation)
            throw std::runtime_error("a second rollback (generation " + std::to_string(c->generation) + ") before the run resumed");
        }
        beat.tick();
        std::this_thread::sleep_for(std::min(beat.until_next(), std::chrono::nanoseconds(1'000'000)));
      }
    };
    auto roll_back = [&](const transport::ControlMessage& command) {
      apply_checkpoint(read_checkpoint(options.run_dir, node_name, command.step));
      generation = command.generation;
      std::printf("rollback: to step %llu (generation %d)\n", static_cast<unsigned long long>(command.step), generation);
      beat.status().message = rolled_back_message(command.step, generation);
      beat.set_state(transport::NodeState::ready);
      if (!await_resume()) return false;
      beat.status().message.clear();
      beat.set_state(transport::NodeState::running);
      go_on_after_rollback();
      return true;
    };
    if (resumed) {
      apply_checkpoint(*resumed);
      std::printf("resumed: from step %llu (generation %d)\n", static_cast<unsigned long long>(header.step), generation);
      go_on_after_rollback();
    }
    bool has_gauss_seidel_input = false;
    for (const auto& edge : node.inputs) has_gauss_seidel_input = has_gauss_seidel_input || edge.order == config::EdgeOrder::gauss_seidel;
    // Low-latency wait: poll with sched_yield for a bounded time before blocking (waking a
    // blocked thread dominates a step's cost on these machines; the price is a busy core).
    auto spin_until_ready = [&](double limit_s) {
      const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limit_s));
      while (Clock::now() < until) {
        drain();
        predict_if_due();
        if (initialised ? stepper.can_step() : stepper.can_initialise()) return true;
        sched_yield();
      }
      return false;
    };
    // A partition (docs/faults.md): waiting longer than the grace for a partner's sample
    // ends the run, naming the partner and its host; a shorter wait is just a stall.
    auto waiting_since = Clock::now();
    std::uint64_t waiting_step = UINT64_MAX;
    auto check_partition = [&] {
      if (stepper.step() != waiting_step || !initialised || within_after_resume(kForeignWriterGrace)) {
        waiting_step = initialised ? stepper.step() : UINT64_MAX;
        waiting_since = Clock::now();
        return;
      }
      const double waited = std::chrono::duration<double>(Clock::now() - waiting_since).count();
      if (waited <= scene.faults.partition_grace) return;
      std::string missing;
      for (std::size_t e = 0; e < node.inputs.size(); ++e)
        if (!stepper.channel(e).ready_for_step(stepper.step())) missing += (missing.empty() ? "" : ", ") + describe_partner(scene, node.inputs[e].from, node.inputs[e].topic);
      if (node.cut && missing.empty()) missing = describe_partner(scene, node.cut->partner, node.cut->partner_topic);
      if (missing.empty())  // an adaptive step waits for the partners' proposals
        for (const std::size_t i : stepper.missing_proposals())
          missing += (missing.empty() ? "" : ", ") + describe_partner(scene, plan.nodes()[i].name(), step_topic(plan.nodes()[i].name()));
      char buf[96];
      std::snprintf(buf, sizeof buf, "no sample for step %llu for %.1f s (faults.partition_grace %g s) from ",
                    static_cast<unsigned long long>(stepper.step()), waited, scene.faults.partition_grace);
      throw std::runtime_error(std::string("unreachable: ") + buf + missing);
    };
    for (;;) {
      drain();
      const bool hold = second_writer_since.has_value() && hold_for_second_writer();
      if (!hold && !initialised && stepper.can_initialise()) {
        stepper.initialise(values);
        publish();
        initialised = true;
      }
      predict_if_due();
      while (initialised && stepper.can_step() && !holding()) {  // a drain below may start a hold
        stepper.step(values);
        if (log)
          if (const auto* row = stepper.event_row()) log->append(stepper.grid().time(stepper.step() - 1), *row);
        publish();
        last_step_taken = Clock::now();
        if (std::exchange(announce_step, false)) beat.send();
        stepper.take_events();  // the block's own event log below says what they meant
        for (const auto& ev : node.block->take_event_log()) log_event(ev, events_file);
        if (stepper.finished()) break;
        if (checkpoint_every > 0 && stepper.step() % static_cast<std::uint64_t>(checkpoint_every) == 0) write_node_checkpoint();
        drain();
        predict_if_due();
        copy_stats(stepper.solver_stats(), beat.status());  // statistics on every heartbeat
        beat.tick();
      }
      if (stepper.finished()) break;
      if (stop_requested() || check_control()) return 3;
      if (pending_rollback) {
        const transport::ControlMessage command = *std::exchange(pending_rollback, std::nullopt);
        if (!roll_back(command)) return 3;
        continue;
      }
      if (holding()) waiting_since = Clock::now();  // a hold is not a partition
      check_partition();
      resend_since_rollback();
      copy_stats(stepper.solver_stats(), beat.status());
      if (pacer && beat.until_next().count() == 0) {  // the figures walk the histogram: heartbeat pace only
        const RealtimeFigures f = pacer->figures();
        beat.status().lateness_max = f.lateness_max;
        beat.status().lateness_p99 = f.lateness_p99;
        beat.status().missed_deadlines = f.missed_deadlines;
        beat.status().rtf_window = f.rtf_window;
      }
      beat.tick();
      if (rt.spin_wait && pacer) {
        // Paced: block until spin_limit before the awaited samples are due, then spin. A
        // node with a Gauss-Seidel input waits for its partners' next step (due at the
        // deadline of the step it publishes next); otherwise for samples of the step it
        // has just published (due now).
        const std::int64_t due = pacer->deadline_ns(stepper.step() + (initialised && has_gauss_seidel_input ? 1 : 0));
        const std::int64_t spin_from = due - static_cast<std::int64_t>(rt.spin_limit * 1e9);
        const std::int64_t now = Pacer::now_ns();
        if (now < spin_from) {
          participant.wait(std::min(beat.until_next(), std::chrono::nanoseconds(spin_from - now)));
          continue;
        }
        if (spin_until_ready(std::max(rt.spin_limit, 1e-9 * static_cast<double>(due - now) + rt.spin_limit))) continue;
      } else if (rt.spin_wait && spin_until_ready(rt.spin_limit)) {
        continue;
      }
      participant.wait(std::min(beat.until_next(), std::chrono::nanoseconds(50'000'000)));
    }
    if (log) log->close();
    if (pacer && !options.run_dir.empty()) write_realtime_figures(options.run_dir + "/" + node_name + ".realtime.json", *pacer);
    writer->flush(std::chrono::seconds(10));
    if (cut_writer) cut_writer->flush(std::chrono::seconds(10));
    if (step_writer) step_writer->flush(std::chrono::seconds(10));
    copy_stats(stepper.solver_stats(), beat.status());
    beat.set_state(transport::NodeState::done);
    std::printf("done: %llu steps, t = %.9g s, %.3f s wall\n", static_cast<unsigned long long>(stepper.step()),
                stepper.time(), beat.elapsed());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", node_name.c_str(), e.what());
    beat.status().message = e.what();
    beat.set_state(transport::NodeState::failed);
    return 1;
  }
}

}  // namespace mechsim::cosim

#include "node_pacing.h"

#include <sched.h>

#include <algorithm>
#include <cstdio>

#include "node_failure.h"

namespace mechsim::cosim {

using Clock = std::chrono::steady_clock;

NodePacing::NodePacing(const ScenePlan& plan, const transport::ControlMessage& start) : scene_(plan.scene()) {
  if (scene_.mode != config::RunMode::realtime) return;
  if (start.start_wall_ns == 0) throw std::runtime_error("realtime mode without a start time in the start command");
  pacer_.emplace(start.start_wall_ns, plan.grid(), scene_.rtf);
}

void NodePacing::wait_for_deadline(std::uint64_t k) {
  if (pacer_) pacer_->wait_for_deadline(k, scene_.realtime.spin_wait ? scene_.realtime.spin_limit : 0.0);
}

void NodePacing::published(std::uint64_t k, double t, NodeStatus& status) {
  if (!pacer_) return;
  const double late = pacer_->published(k);
  const double step_wall = scene_.time.step / scene_.rtf;
  if (scene_.realtime.on_overrun == config::OverrunPolicy::abort && late > step_wall) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "fell behind its deadline by %.3f ms at step %llu (t = %.6g s; a step is %.3f ms of wall time)",
                  late * 1e3, static_cast<unsigned long long>(k), t, step_wall * 1e3);
    throw NodeFailure(transport::NodeError::missed_deadline, buf);
  }
  // Within the first second: a run that cannot keep up at all is told so, with the rate it
  // reaches (it runs flat out while it is late). Under `abort` the first missed deadline
  // has already stopped the run above, so this is a warning only.
  if (!keep_up_checked_ && pacer_->elapsed() > 1.0) {
    keep_up_checked_ = true;
    const RealtimeFigures f = pacer_->figures();
    if (f.missed_deadlines * 2 > f.publications) {
      char buf[256];
      std::snprintf(buf, sizeof buf, "cannot keep up with rtf %g: missed %ld of %ld deadlines in the first second; "
                    "measured maximum rtf %.3g (%.0f steps/s)", scene_.rtf, f.missed_deadlines, f.publications,
                    f.rtf_achieved, f.rtf_achieved / scene_.time.step);
      std::printf("warning: %s\n", buf);
      status.warn(transport::NodeWarning::cannot_keep_up, buf);
    }
  }
}

void NodePacing::report(NodeStatus& status) const {
  if (pacer_ && status.until_next().count() == 0) status.copy_realtime(pacer_->figures());
}

// Low-latency wait: poll with sched_yield for a bounded time before blocking (waking a
// blocked thread dominates a step's cost on these machines; the price is a busy core).
bool NodePacing::spin_until_ready(double limit_s, const std::function<bool()>& poll) const {
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limit_s));
  while (Clock::now() < until) {
    if (poll()) return true;
    sched_yield();
  }
  return false;
}

void NodePacing::wait_for_samples(transport::Participant& participant, const NodeStatus& status, std::uint64_t awaited_step,
                                  const std::function<bool()>& poll, std::chrono::nanoseconds longest) const {
  const config::RealtimeSpec& rt = scene_.realtime;
  if (rt.spin_wait && pacer_) {
    // Paced: block until spin_limit before the awaited samples are due, then spin.
    const std::int64_t due = pacer_->deadline_ns(awaited_step);
    const std::int64_t spin_from = due - static_cast<std::int64_t>(rt.spin_limit * 1e9);
    const std::int64_t now = Pacer::now_ns();
    if (now < spin_from) {
      participant.wait(std::min({status.until_next(), std::chrono::nanoseconds(spin_from - now), longest}));
      return;
    }
    if (spin_until_ready(std::max(rt.spin_limit, 1e-9 * static_cast<double>(due - now) + rt.spin_limit), poll)) return;
  } else if (rt.spin_wait && spin_until_ready(rt.spin_limit, poll)) {
    return;
  }
  participant.wait(std::min({status.until_next(), std::chrono::nanoseconds(50'000'000), longest}));
}

void NodePacing::write_figures(const std::string& path) const {
  if (!pacer_) return;
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (!out) return;
  const RealtimeFigures f = pacer_->figures();
  const LatenessHistogram& h = pacer_->histogram();
  // [bin, count] pairs of the non-empty 1 us bins, for the lateness PNG.
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
  for (const Pacer::Late& l : pacer_->worst()) {
    std::fprintf(out, "%s{\"step\": %llu, \"lateness_s\": %.9g}", first ? "" : ", ", static_cast<unsigned long long>(l.step), l.lateness);
    first = false;
  }
  std::fprintf(out, "]}\n");
  std::fclose(out);
}

}  // namespace mechsim::cosim

#include "mechsim/cosim/pacer.h"

#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>

namespace mechsim::cosim {

std::int64_t Pacer::now_ns() {
  timespec ts;
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

Pacer::Pacer(std::int64_t start_wall_ns, double t0, double macro_step, double rtf)
    : start_ns_(start_wall_ns), t0_(t0), h_(macro_step), rtf_(rtf), window_wall_(start_wall_ns),
      previous_window_wall_(start_wall_ns) {}

std::int64_t Pacer::deadline_ns(std::uint64_t k) const {
  // From the step index, never accumulated: (t_k - t0) / rtf = k H / rtf.
  return start_ns_ + static_cast<std::int64_t>(std::llround(static_cast<double>(k) * h_ / rtf_ * 1e9));
}

void Pacer::wait_for_deadline(std::uint64_t k) const {
  const std::int64_t d = deadline_ns(k);
  timespec ts{static_cast<time_t>(d / 1'000'000'000), static_cast<long>(d % 1'000'000'000)};
  while (clock_nanosleep(CLOCK_REALTIME, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

double Pacer::published(std::uint64_t k) {
  const std::int64_t now = now_ns();
  const double late = std::max<double>(0.0, static_cast<double>(now - deadline_ns(k)) * 1e-9);
  lateness_.push_back(static_cast<float>(late));
  if (late > h_ / rtf_) ++missed_;
  max_late_ = std::max(max_late_, late);
  last_publication_ns_ = now;
  last_k_ = k;
  const double sim = static_cast<double>(k) * h_;
  if (now - window_wall_ >= 1'000'000'000) {
    previous_window_wall_ = window_wall_;
    previous_window_sim_ = window_sim_;
    window_wall_ = now;
    window_sim_ = sim;
  }
  return late;
}

double Pacer::elapsed() const { return static_cast<double>(now_ns() - start_ns_) * 1e-9; }

RealtimeFigures Pacer::running_figures() const {
  RealtimeFigures f;
  f.publications = static_cast<long>(lateness_.size());
  f.missed_deadlines = missed_;
  f.lateness_max = max_late_;
  f.paced_wall_time = static_cast<double>(last_publication_ns_ - start_ns_) * 1e-9;
  const double wall = elapsed();
  const double sim = static_cast<double>(last_k_) * h_;
  f.rtf_achieved = wall > 0 ? sim / wall : 0.0;
  const double window_wall = static_cast<double>(now_ns() - previous_window_wall_) * 1e-9;
  f.rtf_window = window_wall > 0 ? (sim - previous_window_sim_) / window_wall : 0.0;
  return f;
}

RealtimeFigures Pacer::figures() const {
  RealtimeFigures f = running_figures();
  f.publications = static_cast<long>(lateness_.size());
  f.missed_deadlines = missed_;
  if (!lateness_.empty()) {
    std::vector<float> sorted = lateness_;
    std::sort(sorted.begin(), sorted.end());
    auto at = [&](double q) { return static_cast<double>(sorted[std::min(sorted.size() - 1, static_cast<std::size_t>(q * sorted.size()))]); };
    f.lateness_median = at(0.5);
    f.lateness_p99 = at(0.99);
    f.lateness_max = sorted.back();
  }
  return f;
}

}  // namespace mechsim::cosim

#include "mechsim/cosim/pacer.h"

#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace mechsim::cosim {

std::int64_t Pacer::now_ns() {
  timespec ts;
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

Pacer::Pacer(std::int64_t start_wall_ns, std::shared_ptr<const StepGrid> grid, double rtf)
    : start_ns_(start_wall_ns), grid_(std::move(grid)), h_(grid_->nominal_step()), rtf_(rtf), window_wall_(start_wall_ns),
      previous_window_wall_(start_wall_ns) {}

std::int64_t Pacer::deadline_ns(std::uint64_t k) const {
  // From the step index, never accumulated: (t_k - t0) / rtf.
  return start_ns_ + static_cast<std::int64_t>(std::llround(simulated(k) / rtf_ * 1e9));
}

void Pacer::wait_for_deadline(std::uint64_t k, double spin_lead_s) const {
  const std::int64_t d = deadline_ns(k);
  const std::int64_t wake = d - static_cast<std::int64_t>(spin_lead_s * 1e9);
  timespec ts{static_cast<time_t>(wake / 1'000'000'000), static_cast<long>(wake % 1'000'000'000)};
  while (clock_nanosleep(CLOCK_REALTIME, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
  while (spin_lead_s > 0 && now_ns() < d) {
  }
}

double Pacer::published(std::uint64_t k) {
  const std::int64_t now = now_ns();
  const double late = std::max<double>(0.0, static_cast<double>(now - deadline_ns(k)) * 1e-9);
  histogram_.add(late);
  auto least = std::min_element(worst_.begin(), worst_.end(), [](const Late& a, const Late& b) { return a.lateness < b.lateness; });
  if (late > least->lateness) *least = {k, late};
  if (late > h_ / rtf_) ++missed_;
  if (last_publication_ns_ != 0 && k == last_k_ + 1) {
    const double deviation = static_cast<double>(now - last_publication_ns_) * 1e-9 - grid_->step_length(last_k_) / rtf_;
    ++periods_;
    const double delta = deviation - jitter_mean_;
    jitter_mean_ += delta / static_cast<double>(periods_);
    jitter_m2_ += delta * (deviation - jitter_mean_);
    jitter_max_ = std::max(jitter_max_, std::abs(deviation));
  }
  last_publication_ns_ = now;
  last_k_ = k;
  const double sim = simulated(k);
  if (now - window_wall_ >= 1'000'000'000) {
    previous_window_wall_ = window_wall_;
    previous_window_sim_ = window_sim_;
    window_wall_ = now;
    window_sim_ = sim;
  }
  return late;
}

double Pacer::elapsed() const { return static_cast<double>(now_ns() - start_ns_) * 1e-9; }

std::vector<Pacer::Late> Pacer::worst() const {
  std::vector<Late> out;
  for (const Late& l : worst_)
    if (l.lateness > 0) out.push_back(l);
  std::sort(out.begin(), out.end(), [](const Late& a, const Late& b) { return a.lateness > b.lateness; });
  return out;
}

RealtimeFigures Pacer::figures() const {
  RealtimeFigures f;
  f.publications = histogram_.count();
  f.missed_deadlines = missed_;
  f.lateness_median = histogram_.quantile(0.5);
  f.lateness_p99 = histogram_.quantile(0.99);
  f.lateness_max = histogram_.max();
  f.paced_wall_time = static_cast<double>(last_publication_ns_ - start_ns_) * 1e-9;
  const double wall = elapsed();
  const double sim = simulated(last_k_);
  f.rtf_achieved = wall > 0 ? sim / wall : 0.0;
  const double window_wall = static_cast<double>(now_ns() - previous_window_wall_) * 1e-9;
  f.rtf_window = window_wall > 0 ? (sim - previous_window_sim_) / window_wall : 0.0;
  f.period_jitter_std = periods_ > 1 ? std::sqrt(jitter_m2_ / static_cast<double>(periods_ - 1)) : 0.0;
  f.period_jitter_max = jitter_max_;
  return f;
}

}  // namespace mechsim::cosim

// Real-time pacing of one node: step k is published no earlier than
//   t_start + (t_k - t_0) / rtf
// (t_start from the launcher's start command, wall clock), and every publication's
// lateness against that deadline is recorded. Pacing only delays publication: the numbers
// are those of a lock-step run.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mechsim/cosim/lateness_histogram.h"
#include "mechsim/cosim/step_grid.h"

namespace mechsim::cosim {

struct RealtimeFigures {
  double lateness_median = 0, lateness_p99 = 0, lateness_max = 0;  // s
  long missed_deadlines = 0;     // publications later than one macro step (of wall time)
  long publications = 0;
  double rtf_achieved = 0;       // simulated time / wall time since the start
  double rtf_window = 0;         // over the last second of wall time
  double paced_wall_time = 0;    // s from the start time (step 0 due) to the last publication
  // Jitter of the publication period: the spread of (t_pub,k - t_pub,k-1) around the
  // nominal H / rtf, standard deviation and largest deviation.
  double period_jitter_std = 0, period_jitter_max = 0;  // s
};

class Pacer {
 public:
  // start_wall_ns: Unix time (CLOCK_REALTIME) of step 0; step k is due (t_k - t_0) / rtf
  // later, t_k from the run's grid (a step shortened to land on an event is due earlier).
  Pacer(std::int64_t start_wall_ns, std::shared_ptr<const StepGrid> grid, double rtf);
  // Sleeps until step k's deadline (returns at once when already late). With spin_lead > 0
  // it sleeps until spin_lead before the deadline and polls the clock from there: a timer
  // wake-up on a loaded or virtual machine is tens of microseconds late, a poll is not.
  void wait_for_deadline(std::uint64_t k, double spin_lead_s = 0.0) const;
  // Wall time (Unix ns) step k is due.
  std::int64_t deadline_ns(std::uint64_t k) const;
  // Records the publication of step k now; returns its lateness in s.
  double published(std::uint64_t k);
  // Every figure so far. Walks the histogram (20 000 bins): call it at heartbeat pace, not
  // every step.
  RealtimeFigures figures() const;
  const LatenessHistogram& histogram() const { return histogram_; }
  // The latest publications (step, lateness in s), worst first: to find what caused them
  // (a step of the model, a stall of the machine: several nodes late at the same step).
  struct Late {
    std::uint64_t step = 0;
    double lateness = 0;
  };
  static constexpr std::size_t kWorst = 8;
  std::vector<Late> worst() const;
  // Seconds of wall time since the start.
  double elapsed() const;
  static std::int64_t now_ns();

 private:
  double simulated(std::uint64_t k) const { return grid_->time(k) - grid_->start(); }
  std::int64_t start_ns_;
  std::shared_ptr<const StepGrid> grid_;
  double h_, rtf_;  // h_: the nominal step, what a deadline may be missed by
  LatenessHistogram histogram_;
  std::array<Late, kWorst> worst_{};  // unsorted; fixed size: no allocation per step
  long missed_ = 0;
  std::int64_t last_publication_ns_ = 0;
  // Welford sums of the period deviation from nominal (from the second publication on).
  long periods_ = 0;
  double jitter_mean_ = 0, jitter_m2_ = 0, jitter_max_ = 0;
  std::uint64_t last_k_ = 0;
  // (wall, simulated) at the start of the current and the previous one-second window
  std::int64_t window_wall_ = 0, previous_window_wall_ = 0;
  double window_sim_ = 0, previous_window_sim_ = 0;
};

}  // namespace mechsim::cosim

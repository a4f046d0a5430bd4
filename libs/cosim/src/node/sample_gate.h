// The one gate every incoming sample passes before the stepper sees it (docs/faults.md,
// 'Foreign writers', 'Redundant samples'): nobody else writes into the run, so each input
// topic has exactly the one writer the scene plans, its samples belong to this run and
// come one step after the other, their values are plausible, and the redundant copy of a
// step carries the same values (a duplicate is dropped). Partner predictions of the cut
// and step proposals pass it too.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mechsim/cosim/node_stepper.h"
#include "mechsim/cosim/scene_plan.h"
#include "node_endpoints.h"
#include "rollback_session.h"
#include "steady_now.h"

namespace mechsim::cosim {

class SampleGate {
 public:
  // resumed: a node restarted from a checkpoint takes up each stream wherever it is. now:
  // the clock of the second-writer grace (steady_now.h; a unit test steps its own).
  SampleGate(const ScenePlan& plan, const PlannedNode& node, NodeEndpoints& io, NodeStepper& stepper,
             const RollbackSession& rollback, std::uint64_t run_id, int domain, bool resumed, SteadyNow now = steady_now);

  // Takes every waiting sample, checks it and hands it to the stepper. Throws NodeFailure
  // (foreign data, implausible input).
  void drain();
  // True while a second writer makes the node hold (use no sample); throws once it
  // outstayed the grace. hold(): the same, checked only when a second writer was seen.
  bool hold() { return second_writer_since_.has_value() && hold_for_second_writer(); }
  // Holding, without looking at the writers again (a drain may start a hold).
  bool holding() const;

 private:
  bool in_sequence(std::size_t e, std::uint64_t step) const;
  bool hold_for_second_writer();
  void check_plausible(std::size_t e, const transport::SampleHeader& h, const std::vector<double>& v);
  bool drain_input(std::size_t e);
  [[noreturn]] void foreign(const transport::SampleReader* r, const std::string& topic, const std::string& from,
                            const std::string& what) const;

  const ScenePlan& plan_;
  const PlannedNode& node_;
  NodeEndpoints& io_;
  NodeStepper& stepper_;
  const RollbackSession& rollback_;
  std::uint64_t run_id_;
  int domain_;
  SteadyNow now_;
  std::vector<std::uint64_t> next_step_;
  std::vector<bool> next_step_known_;
  std::vector<std::vector<int>> checked_fields_;  // per input edge: the fields its publisher computes
  std::optional<std::chrono::steady_clock::time_point> second_writer_since_;
  std::vector<double> received_;
};

}  // namespace mechsim::cosim

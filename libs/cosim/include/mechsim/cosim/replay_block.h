// A participant stood in for by a recording (`mechsim launch --replay NODE=FILE`,
// docs/recording.md): a block with the replaced block's ports whose outputs at step k are
// the values its topic carried at step k in the recording, bit for bit. The node around it
// is the ordinary node (readiness, lock-step gating on the same inbound edges, status,
// output log), so live partners receive exactly what the original run sent them, when the
// protocol says they need it.
#pragma once

#include <memory>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/cosim/step_grid.h"
#include "mechsim/models/block.h"

namespace mechsim::cosim {

// The recorded topic of one participant: rows[k] holds the topic's field values at step k
// (in the field order of its type), for k = 0 .. steps.
struct RecordedTopic {
  std::vector<std::vector<double>> rows;
  std::vector<double> times;  // t_k of each row (the samples' own instants)
};

class ReplayBlock final : public models::Block {
 public:
  // `published_outputs`: the replaced block's output index of each topic field (-1: none),
  // as in PlannedNode. The replay has the replaced block's inputs and, as outputs, only
  // those a topic field carries (a recording knows nothing else), in field order.
  ReplayBlock(const models::Block& replaced, const std::vector<int>& published_outputs, RecordedTopic recorded,
              std::shared_ptr<const StepGrid> grid);
  void calc_outputs(double t, std::span<const double> x, std::span<const double> u, std::span<double> y) const override;
  // The recorded run's instants: a replay of an adaptive run steps where it stepped.
  double next_instant_after(double t) const override;
  // The topic field of each output: the node's published_outputs for this block.
  std::vector<int> published_outputs() const;

 private:
  std::vector<int> field_of_output_;
  RecordedTopic recorded_;
  std::shared_ptr<const StepGrid> grid_;
};

// The table `mechsim launch` writes for a replayed node: an output log (output_log.h) with
// the columns "t" and the topic's field names, one row per step.
RecordedTopic recorded_topic_from_log(const OutputLog& log, const transport::TopicType& type, const std::string& path);

// Replaces `node`'s block by a ReplayBlock over `recorded` (and its published_outputs to
// match). Throws std::runtime_error when the recording does not cover every step.
void replace_with_replay(PlannedNode& node, RecordedTopic recorded, std::shared_ptr<const StepGrid> grid);

}  // namespace mechsim::cosim

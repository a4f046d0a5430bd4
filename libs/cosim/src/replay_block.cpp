#include "mechsim/cosim/replay_block.h"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>

namespace mechsim::cosim {

ReplayBlock::ReplayBlock(const models::Block& replaced, const std::vector<int>& published_outputs, RecordedTopic recorded,
                         std::shared_ptr<const StepGrid> grid)
    : models::Block(replaced.type_name() + " (replayed)"), recorded_(std::move(recorded)), grid_(std::move(grid)) {
  // The same inputs, so that the scene's edges map onto it unchanged (and the node waits
  // for its partners exactly as the original did). No output feeds through: a recording
  // does not depend on what the partners send now.
  for (const auto& in : replaced.inputs()) declare_input(in.name, in.unit, in.default_value);
  for (std::size_t f = 0; f < published_outputs.size(); ++f) {
    if (published_outputs[f] < 0) continue;
    const auto& out = replaced.outputs()[static_cast<std::size_t>(published_outputs[f])];
    declare_output(out.name, out.unit);
    field_of_output_.push_back(static_cast<int>(f));
  }
}

std::vector<int> ReplayBlock::published_outputs() const {
  std::vector<int> of_field;
  for (std::size_t o = 0; o < field_of_output_.size(); ++o) {
    const auto f = static_cast<std::size_t>(field_of_output_[o]);
    if (of_field.size() <= f) of_field.resize(f + 1, -1);
    of_field[f] = static_cast<int>(o);
  }
  return of_field;
}

void ReplayBlock::calc_outputs(double t, std::span<const double>, std::span<const double>, std::span<double> y) const {
  // Outputs are asked for at the grid's instants (computed from k), so k is found exactly.
  const std::optional<std::uint64_t> k = grid_->step_at(t);
  if (!k || *k >= recorded_.rows.size())
    throw std::runtime_error("replay: the recording has no sample for t = " + std::to_string(t) + " s");
  const auto& row = recorded_.rows[static_cast<std::size_t>(*k)];
  for (std::size_t o = 0; o < field_of_output_.size(); ++o) y[o] = row.at(static_cast<std::size_t>(field_of_output_[o]));
}

double ReplayBlock::next_instant_after(double t) const {
  if (!grid_->is_adaptive()) return Block::next_instant_after(t);
  const auto it = std::upper_bound(recorded_.times.begin(), recorded_.times.end(), t);
  return it == recorded_.times.end() ? Block::next_instant_after(t) : *it;
}

RecordedTopic recorded_topic_from_log(const OutputLog& log, const transport::TopicType& type, const std::string& path) {
  RecordedTopic r;
  std::vector<int> columns;
  for (const auto& field : type.fields) {
    const int c = log.column(field.name);
    if (c < 0) throw std::runtime_error(path + ": no column '" + field.name + "' of " + type.idl_name);
    columns.push_back(c);
  }
  r.rows.resize(log.rows());
  r.times = log.data.empty() ? std::vector<double>{} : log.data[0];
  for (std::size_t k = 0; k < log.rows(); ++k)
    for (int c : columns) r.rows[k].push_back(log.data[static_cast<std::size_t>(c)][k]);
  return r;
}

void replace_with_replay(PlannedNode& node, RecordedTopic recorded, std::shared_ptr<const StepGrid> grid) {
  if (grid->is_adaptive() && (recorded.times.empty() || recorded.times.back() != grid->end()))
    throw std::runtime_error("replay of '" + node.name() + "': the recording of this adaptive run does not reach its end (" +
                             std::to_string(grid->end()) + " s)");
  const auto needed = grid->is_adaptive() ? recorded.rows.size() : static_cast<std::size_t>(grid->steps()) + 1;
  if (recorded.rows.size() < needed)
    throw std::runtime_error("replay of '" + node.name() + "': the recording holds " +
                             (recorded.rows.empty() ? std::string("no step") : "steps 0.." + std::to_string(recorded.rows.size() - 1)) +
                             " of its topic, the scene needs steps 0.." + std::to_string(needed - 1));
  auto replay = std::make_unique<ReplayBlock>(*node.block, node.published_outputs, std::move(recorded), std::move(grid));
  std::vector<int> published = replay->published_outputs();
  published.resize(node.published_outputs.size(), -1);
  node.published_outputs = std::move(published);
  node.block = std::move(replay);
}

}  // namespace mechsim::cosim

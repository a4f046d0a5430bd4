#include "node_endpoints.h"

#include <chrono>

#include "mechsim/cosim/step_topic.h"

namespace mechsim::cosim {

NodeEndpoints::NodeEndpoints(ScenePlan& plan, const std::string& node_name, transport::Participant& participant, bool redundant)
    : node_(plan.node(node_name)) {
  const PlannedNode& node = node_;
  writer_ = participant.create_writer(node.topic, *node.type->publishes);
  for (const auto& edge : node.inputs) readers_.push_back(participant.create_reader(edge.topic, *edge.type));
  if (node.cut) {
    cut_writer_ = participant.create_writer(node.cut->topic, *node.cut->type);
    cut_reader_ = participant.create_reader(node.cut->partner_topic, *node.cut->type);
  }
  // Redundant samples (docs/faults.md): every sample also on the best-effort twin topic;
  // whichever copy of a step arrives first is used, the other is a duplicate the input
  // channels drop. Not part of readiness: a twin that loses its first samples costs nothing.
  if (redundant) {
    twin_writer_ = participant.create_redundant_writer(node.topic, *node.type->publishes);
    for (const auto& edge : node.inputs) twin_readers_.push_back(participant.create_redundant_reader(edge.topic, *edge.type));
    if (node.cut) {
      twin_cut_writer_ = participant.create_redundant_writer(node.cut->topic, *node.cut->type);
      twin_cut_reader_ = participant.create_redundant_reader(node.cut->partner_topic, *node.cut->type);
    }
  }
  // Adaptive macro step: this node's proposals out, every other participant's in
  // (step_control.h; the proposals of one step agree in every node without the launcher).
  while (plan.nodes()[self_].name() != node_name) ++self_;
  if (plan.grid()->is_adaptive()) {
    const transport::TopicType& type = step_proposal_type();
    step_writer_ = participant.create_writer(step_topic(node_name), type);
    for (std::size_t i = 0; i < plan.nodes().size(); ++i)
      if (i != self_) {
        const std::string topic = step_topic(plan.nodes()[i].name());
        step_readers_.push_back({i, topic, participant.create_reader(topic, type)});
      }
  }
  for (std::size_t e = 0; e < readers_.size(); ++e) {
    watched_.push_back({readers_[e].get(), node.inputs[e].topic, node.inputs[e].from});
    if (e < twin_readers_.size() && twin_readers_[e])
      watched_.push_back({twin_readers_[e].get(), transport::redundant_topic(node.inputs[e].topic), node.inputs[e].from});
  }
  if (cut_reader_) watched_.push_back({cut_reader_.get(), node.cut->partner_topic, node.cut->partner});
  if (twin_cut_reader_) watched_.push_back({twin_cut_reader_.get(), transport::redundant_topic(node.cut->partner_topic), node.cut->partner});
}

bool NodeEndpoints::matched() const {
  if (writer_->matched_readers() < node_.subscriber_count) return false;
  if (node_.recorded && writer_->matched_readers_including_tools() < node_.subscriber_count + 1) return false;
  for (const auto& r : readers_)
    if (r->matched_writers() < 1) return false;
  if (step_writer_ && step_writer_->matched_readers() < static_cast<int>(step_readers_.size())) return false;
  for (const auto& r : step_readers_)
    if (r.reader->matched_writers() < 1) return false;
  return !node_.cut || (cut_writer_->matched_readers() >= 1 && cut_reader_->matched_writers() >= 1);
}

void NodeEndpoints::write_own(const transport::SampleHeader& h, const std::vector<double>& v) {
  writer_->write(h, v);
  if (twin_writer_) twin_writer_->write(h, v);
}

void NodeEndpoints::write_prediction(const transport::SampleHeader& h, const std::vector<double>& v) {
  cut_writer_->write(h, v);
  if (twin_cut_writer_) twin_cut_writer_->write(h, v);
}

void NodeEndpoints::write_proposal(const transport::SampleHeader& h, const std::vector<double>& fields) {
  step_writer_->write(h, fields);
}

void NodeEndpoints::flush() {
  writer_->flush(std::chrono::seconds(10));
  if (cut_writer_) cut_writer_->flush(std::chrono::seconds(10));
  if (step_writer_) step_writer_->flush(std::chrono::seconds(10));
}

}  // namespace mechsim::cosim

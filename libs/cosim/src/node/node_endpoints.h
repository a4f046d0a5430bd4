// The node's DDS endpoints and its readiness: its data writer and its input readers, the
// interface-Jacobian cut (its predictions out, the partner's in), the redundant twins of
// all of them (faults.redundant_samples), and an adaptive step's proposals.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mechsim/cosim/scene_plan.h"
#include "mechsim/transport/participant.h"

namespace mechsim::cosim {

// A reader of a partner's samples, with the topic and the participant it expects.
struct WatchedReader {
  const transport::SampleReader* reader;
  std::string topic, from;
};

class NodeEndpoints {
 public:
  NodeEndpoints(ScenePlan& plan, const std::string& node_name, transport::Participant& participant, bool redundant);

  // Matched both ways with every partner (docs/protocol.md: a match seen by only one side
  // can lose the first sample); a recorded node also with the recorder.
  bool matched() const;
  // Readers matched with the data writer over DDS, tools' included (the launcher starts the
  // run once every reader on the domain, a recorder of the user's included, is matched; a
  // co-located member reading from memory is no reader on the domain).
  int readers_matched_including_tools() const { return writer_->matched_readers_on_the_wire(); }

  // Every write of the node's own sample and of its cut prediction, each with its twin.
  void write_own(const transport::SampleHeader& h, const std::vector<double>& v);
  void write_prediction(const transport::SampleHeader& h, const std::vector<double>& v);
  void write_proposal(const transport::SampleHeader& h, const std::vector<double>& fields);
  bool has_cut() const { return cut_writer_ != nullptr; }
  // Waits until the last samples are acknowledged (at the end of the run).
  void flush();

  // Input edge e's reader and its twin (null without redundant samples).
  std::size_t inputs() const { return readers_.size(); }
  transport::SampleReader& input(std::size_t e) { return *readers_[e]; }
  transport::SampleReader* twin_input(std::size_t e) { return e < twin_readers_.size() ? twin_readers_[e].get() : nullptr; }
  // The partner's cut predictions and their twin (null: none).
  transport::SampleReader* cut_input() { return cut_reader_.get(); }
  transport::SampleReader* twin_cut_input() { return twin_cut_reader_.get(); }
  // Every other participant's step proposals (adaptive step), by plan index.
  struct ProposalReader {
    std::size_t participant;
    std::string topic;
    std::unique_ptr<transport::SampleReader> reader;
  };
  std::vector<ProposalReader>& proposal_inputs() { return step_readers_; }
  // Every reader of a partner's samples, twins included (the writer-identity check).
  const std::vector<WatchedReader>& watched() const { return watched_; }
  std::size_t self() const { return self_; }

 private:
  const PlannedNode& node_;
  std::size_t self_ = 0;
  std::unique_ptr<transport::SampleWriter> writer_, cut_writer_, twin_writer_, twin_cut_writer_, step_writer_;
  std::vector<std::unique_ptr<transport::SampleReader>> readers_, twin_readers_;
  std::unique_ptr<transport::SampleReader> cut_reader_, twin_cut_reader_;
  std::vector<ProposalReader> step_readers_;
  std::vector<WatchedReader> watched_;
};

}  // namespace mechsim::cosim

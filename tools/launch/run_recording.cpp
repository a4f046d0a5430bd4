#include "run_recording.h"

#include <filesystem>
#include <stdexcept>

#include "mechsim/cosim/step_topic.h"
#include "mechsim/transport/backends.h"
#include "mechsim/transport/topic_types.h"
#include "cdr_decoder.h"
#include "recorder.h"

namespace mechsim::launch {

namespace fs = std::filesystem;

std::unique_ptr<RunRecording> RunRecording::start(const cosim::ScenePlan& plan, int domain_id, const std::string& run_dir) {
  const config::Scene& scene = plan.scene();
  if (!scene.record) return nullptr;
  const config::RecordSpec& spec = *scene.record;
  recorder::RecordOptions options;
  options.file = fs::path(spec.file).is_absolute() ? spec.file : (fs::path(run_dir) / spec.file).string();
  options.topics.names = spec.topics;
  options.topics.regex = spec.regex;
  options.compression = recorder::parse_compression(spec.compression);
  // Readers before the writers exist: nothing of step 0 is missed. The control topic is
  // transient-local (the start command reaches a late reader anyway); status is a best-effort
  // heartbeat found through discovery.
  std::unique_ptr<RunRecording> r(new RunRecording());
  for (const auto& node : plan.nodes())
    if (options.topics.selects(node.topic)) {
      options.topic_types[node.topic] = node.type->publishes->idl_name;
      if (node.type->publishes->layout == transport::TopicLayout::sequences)
        options.topic_fields[node.topic] = recorder::fields_text(recorder::layout_of(*node.type->publishes));
      r->data_topics_.push_back(node.topic);
    }
  // An adaptive step's proposals (<node>/step): each node's error estimate at every step.
  if (plan.grid()->is_adaptive())
    for (const auto& node : plan.nodes())
      if (const std::string topic = cosim::step_topic(node.name()); options.topics.selects(topic))
        options.topic_types[topic] = cosim::step_proposal_type().idl_name;
  if (options.topics.selects(transport::kControlTopic)) options.topic_types[transport::kControlTopic] = "mechsim::msg::Control";
  r->file_ = options.file;
  r->recorder_ = recorder::start_recording(domain_id, options);
  return r;
}

RunRecording::~RunRecording() {
  if (recorder_) recorder_->stop();  // idempotent: closes the file on every path
}

bool RunRecording::wait_matched(std::chrono::milliseconds timeout) { return recorder_->wait_matched(data_topics_, timeout); }

nlohmann::json RunRecording::finish(const std::map<std::string, std::uint64_t>& published_by_topic) {
  const recorder::RecordingReport report = recorder_->stop();
  nlohmann::json topics = nlohmann::json::array();
  bool complete = report.error.empty();
  for (const auto& t : report.topics) {
    nlohmann::json row{{"topic", t.topic}, {"type", t.type}, {"reliable", t.reliable}, {"recorded", t.samples}};
    if (!t.reliable) row["lost"] = t.lost;
    if (t.repeated > 0) row["repeated_after_rollback"] = t.repeated;
    if (auto it = published_by_topic.find(t.topic); it != published_by_topic.end()) {
      row["published"] = it->second;
      row["complete"] = t.samples == it->second;
      complete = complete && t.samples == it->second;
    }
    topics.push_back(row);
  }
  nlohmann::json j{{"file", report.file}, {"bytes", report.bytes}, {"messages", report.messages},
                   {"complete", complete}, {"topics", topics}};
  if (!report.error.empty()) j["error"] = report.error;
  return j;
}

}  // namespace mechsim::launch

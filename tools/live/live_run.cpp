#include "live_run.h"

#include "cdr_decoder.h"
#include "mechsim/transport/topic_types.h"

namespace mechsim::live {

LiveRun::LiveRun(const cosim::ScenePlan& plan, const RunIdentity& run, const LiveOptions& options) {
  LiveOptions o = options;
  o.name = "mechsim " + run.scene + " run " + run.run_id;
  o.session_id = run.run_id;
  o.metadata = {{"scene", run.scene}, {"scene_file", run.scene_file}, {"run_id", run.run_id},
                {"run_dir", run.run_dir}, {"domain", std::to_string(run.domain)}};
  server_ = std::make_unique<LiveServer>(o);
  DomainSourceOptions d;
  d.domain = run.domain;
  for (const auto& node : plan.nodes()) {
    d.topic_types[node.topic] = node.type->publishes->idl_name;
    if (node.type->publishes->layout == transport::TopicLayout::sequences)
      d.topic_fields[node.topic] = recorder::fields_text(recorder::layout_of(*node.type->publishes));
  }
  d.topic_types[transport::kControlTopic] = "mechsim::msg::Control";
  d.topic_types[transport::kStatusTopic] = "mechsim::msg::Status";
  source_ = std::make_unique<DomainSource>(*server_, d);
}

LiveRun::~LiveRun() {
  source_.reset();
  server_.reset();
}

std::string LiveRun::describe() const {
  const std::string& a = server_->options().address;
  const std::string host = (a.find(':') != std::string::npos ? "[" + a + "]" : a) + ":" + std::to_string(port());
  return "ws://" + host + " (Foxglove WebSocket), page http://" + host + "/";
}

}  // namespace mechsim::live

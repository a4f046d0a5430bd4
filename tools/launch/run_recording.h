// A scene's `record:` section at run time (docs/recording.md): the recorder's readers exist
// before the node processes start, so step 0 is recorded; the run starts only when every
// recorded data topic is matched with its writer; the file is closed on every path (done,
// failed, interrupted) and the summary compares samples recorded with samples published.
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "mechsim/cosim/scene_plan.h"

namespace mechsim::recorder {
class Recorder;
}

namespace mechsim::launch {

class RunRecording {
 public:
  // nullptr when the scene has no `record:` section. Throws std::runtime_error when the
  // recorder cannot start (no Cyclone DDS in this build, the file cannot be created).
  static std::unique_ptr<RunRecording> start(const cosim::ScenePlan& plan, int domain_id, const std::string& run_dir);
  ~RunRecording();

  // True when the reader of every recorded data topic is matched with its writer.
  bool wait_matched(std::chrono::milliseconds timeout);
  // Stops the recorder and describes the file: per topic the samples recorded and, for the
  // nodes' data topics, the samples published (from each node's output log: one row per
  // published step), `complete` when they agree.
  nlohmann::json finish(const std::map<std::string, std::uint64_t>& published_by_topic);
  const std::string& file() const { return file_; }

 private:
  RunRecording() = default;
  std::unique_ptr<recorder::Recorder> recorder_;
  std::vector<std::string> data_topics_;
  std::string file_;
};

}  // namespace mechsim::launch

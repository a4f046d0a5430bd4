// `mechsim launch SCENE --live [ADDRESS:]PORT`: the live server of one run. Its readers
// exist before the nodes start, one channel per topic of the run (the participants' data
// topics, an FMU participant's with its variable names, control, status, and whatever
// else appears, e.g. an adaptive run's step proposals); serverInfo names the run. The
// run does not wait for it: readers() is what the launcher's barrier leaves out.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <utility>

#include "domain_source.h"
#include "live_server.h"
#include "mechsim/cosim/scene_plan.h"

namespace mechsim::live {

struct RunIdentity {
  std::string scene, scene_file, run_id, run_dir;
  int domain = 0;
};

class LiveRun {
 public:
  // Throws std::invalid_argument / std::runtime_error (the port taken, DDS refusing).
  LiveRun(const cosim::ScenePlan& plan, const RunIdentity& run, const LiveOptions& options);
  ~LiveRun();
  std::uint16_t port() const { return server_->port(); }
  // "ws://ADDRESS:PORT" and "http://ADDRESS:PORT/", for the launcher's line.
  std::string describe() const;
  std::map<std::pair<std::string, std::string>, int> readers() const { return source_->readers(); }
  LiveStats stats() const { return server_->stats(); }

 private:
  std::unique_ptr<LiveServer> server_;
  std::unique_ptr<DomainSource> source_;  // after server_: stopped first
};

}  // namespace mechsim::live

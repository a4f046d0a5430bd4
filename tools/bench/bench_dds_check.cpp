#include "bench_runner.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "launch_process.h"

namespace mechsim::bench {

namespace {

bool same_bytes(const std::string& a, const std::string& b) {
  std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
  if (!fa || !fb) return false;
  std::string sa((std::istreambuf_iterator<char>(fa)), {}), sb((std::istreambuf_iterator<char>(fb)), {});
  return sa == sb;
}

}  // namespace

// The same run as real node processes through `mechsim launch`, its error as the launcher
// reports it, and whether every node's output log equals the in-process run's byte for byte.
json Bench::dds_check(const RunSpec& r, const RunResult& inproc) {
  const std::string exe = opt_.mechsim_exe.empty() ? this_executable() : opt_.mechsim_exe;
  const std::string dir = opt_.work_dir + "/dds-" + std::to_string(++run_counter_);
  const LaunchedRun launched = run_mechsim_launch(exe, variant_files_[r.variant], run_overrides(r, true), dir);
  json out{{"scheme", variants_[r.variant].name}, {"step_s", r.h}, {"solver", r.solver}, {"rtol", r.rtol},
           {"launch_exit", launched.exit_code}, {"process_time_s", launched.process_time_s}};
  if (!launched.summary) {
    out["status"] = "failed";
    out["reason"] = "no summary from mechsim launch (see " + launched.log_path + ")";
    return out;
  }
  const json& summary = *launched.summary;
  out["status"] = summary.value("status", "?");
  out["wall_time_s"] = summary.value("wall_time_s", kNaN);
  out["inproc_wall_time_s"] = finite_or_null(inproc.wall_time_s);
  const std::string run_dir = summary.value("run_dir", "");
  // Equal outcomes: both ran through, or both stopped (the launcher reports "failed" for a
  // diverged node); and the node logs equal byte for byte up to where they stopped.
  out["inproc_status"] = inproc.status;
  const bool dds_ok = out["status"] == "ok", inproc_ok = inproc.completed;
  bool identical = !run_dir.empty() && dds_ok == inproc_ok;
  json nodes = json::object();
  for (const auto& p : participants_) {
    const bool same = same_bytes(inproc.run_dir + "/" + p + ".outputs.bin", run_dir + "/" + p + ".outputs.bin");
    nodes[p] = same;
    identical = identical && same;
  }
  out["outputs_identical"] = identical;
  out["nodes_identical"] = nodes;
  // The launcher's figures next to the bench's (the same code computes both).
  json diff = json::object();
  double worst = 0;
  if (summary.contains("signals"))
    for (auto& [name, s] : summary["signals"].items()) {
      if (!inproc.signals.contains(name) || !inproc.signals[name].contains("rms_abs_error")) continue;
      const json& b = inproc.signals[name]["rms_abs_error"];
      const double dds_rms = s.value("rms_abs_error", kNaN);
      if (b.is_number()) {
        const double d = std::abs(dds_rms - b.get<double>());
        worst = std::max(worst, std::isfinite(d) ? d : std::numeric_limits<double>::infinity());
      }
      diff[name] = {{"dds_rms_abs_error", finite_or_null(dds_rms)}, {"inproc_rms_abs_error", b}};
    }
  out["signals"] = diff;
  out["max_rms_abs_difference"] = finite_or_null(worst);
  out["run_dir"] = run_dir;
  return out;
}

}  // namespace mechsim::bench

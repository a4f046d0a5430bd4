#include "launch_process.h"

#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>

#include "elapsed.h"

namespace mechsim::bench {

namespace fs = std::filesystem;

namespace {

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

LaunchedRun run_mechsim_launch(const std::string& exe, const std::string& scene_file,
                               const std::vector<std::string>& overrides, const std::string& dir) {
  fs::create_directories(dir);
  LaunchedRun run;
  run.log_path = dir + "/launch.log";
  std::string cmd = shell_quote(exe) + " launch " + shell_quote(scene_file);
  for (const auto& o : overrides) cmd += " --set " + shell_quote(o);
  cmd += " --json " + shell_quote(dir + "/summary.json") + " --runs-dir " + shell_quote(dir) + " --no-plot --no-progress";
  cmd += " >" + shell_quote(run.log_path) + " 2>&1";
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = std::system(cmd.c_str());
  run.process_time_s = seconds_since(t0);
  run.exit_code = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  try {
    std::ifstream f(dir + "/summary.json");
    run.summary = nlohmann::json::parse(f);
  } catch (const std::exception&) {
    run.summary.reset();
  }
  return run;
}

std::string this_executable() {
  std::string exe = fs::read_symlink("/proc/self/exe").string();
  // A rebuilt executable while the bench runs: the link names the old, deleted file.
  const std::string deleted = " (deleted)";
  if (exe.size() > deleted.size() && exe.compare(exe.size() - deleted.size(), deleted.size(), deleted) == 0)
    exe.resize(exe.size() - deleted.size());
  return exe;
}

}  // namespace mechsim::bench

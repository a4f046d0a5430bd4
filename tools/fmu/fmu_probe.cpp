#include "fmu_probe.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/fmu_probe.h"
#include "mechsim/cosim/fmu_unpacking.h"
#include "mechsim/fmi/archive.h"
#include "mechsim/fmi/error.h"

extern char** environ;

namespace mechsim::tools {

namespace fs = std::filesystem;
using nlohmann::json;

int run_fmu_probe(const std::string& scene_file, const std::vector<std::string>& overrides, const std::string& participant,
                  const std::string& unpack_dir) {
  json out{{"participant", participant}, {"file", ""}, {"ok", false}, {"error", ""}};
  int code = 0;
  try {
    if (!unpack_dir.empty()) fmi::set_unpack_root(unpack_dir);
    const config::Scene scene = config::load_scene(scene_file, overrides);
    cosim::defer_fmu_instantiation();  // only this participant's FMU, below
    const cosim::ScenePlan plan = cosim::ScenePlan::build(scene);
    for (const auto& f : cosim::planned_fmus(plan))
      if (f.participant == participant) out["file"] = f.file;
    if (out["file"] == "") throw config::ConfigError(scene.file, "participants." + participant, "expected a participant played by an FMU");
    cosim::instantiate_fmu(plan, participant);
    out["ok"] = true;
  } catch (const config::ConfigError& e) {
    out["error"] = e.what();
    code = 2;
  } catch (const std::exception& e) {
    out["error"] = e.what();
    code = 1;
  }
  std::fputs((out.dump() + "\n").c_str(), stdout);
  return code;
}

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The last line of `text` that parses as a JSON object (the child's answer).
json answer_in(const std::string& text) {
  std::istringstream lines(text);
  json found;
  for (std::string line; std::getline(lines, line);)
    if (!line.empty() && line.front() == '{')
      if (json j = json::parse(line, nullptr, false); j.is_object()) found = j;
  return found;
}

std::string how_it_ended(int status) {
  if (WIFSIGNALED(status))
    return "killed by signal " + std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) + ")";
  return "exit code " + std::to_string(WEXITSTATUS(status));
}

// One child: `mechsim fmu probe` with its output in `output_file`; returns its wait status.
int run_child(const std::vector<std::string>& args, const fs::path& output_file) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, output_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int failed = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (failed != 0) throw std::runtime_error("cannot start " + args[0] + ": " + std::strerror(failed));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

}  // namespace

std::string probe_fmus_in_children(const std::string& scene_file, const std::vector<std::string>& overrides,
                                   const cosim::ScenePlan& plan, const std::string& unpack_dir) {
  const auto fmus = cosim::planned_fmus(plan);
  if (fmus.empty()) return "";
  // A folder of this call's for the FMUs and the children's output, removed however they ended.
  std::string scratch_pattern = (fs::temp_directory_path() / "mechsim-fmu-probe-XXXXXX").string();
  if (mkdtemp(scratch_pattern.data()) == nullptr) return "cannot create a folder under " + fs::temp_directory_path().string();
  const fs::path scratch = scratch_pattern;
  struct Remove {
    fs::path p;
    ~Remove() {
      std::error_code ec;
      fs::remove_all(p, ec);
    }
  } remove{scratch};
  const std::string unpack = unpack_dir.empty() ? (scratch / "fmu").string() : unpack_dir;
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  for (const auto& f : fmus) {
    std::vector<std::string> args{self, "fmu", "probe", scene_file, "--participant", f.participant, "--unpack-dir", unpack};
    for (const auto& o : overrides) args.insert(args.end(), {"--set", o});
    const fs::path output = scratch / (f.participant + ".out");
    const int status = run_child(args, output);
    const std::string text = slurp(output);
    const json answer = answer_in(text);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && answer.value("ok", false)) continue;
    if (answer.is_object() && !answer.value("error", std::string()).empty()) return answer["error"].get<std::string>();
    // No answer: the FMU took the child down (abort, a segmentation fault, exit()).
    std::string why = fmi::FmuLabel{f.file, f.participant}.describe() + ": the child process that instantiates it (`mechsim fmu probe`) " +
                      how_it_ended(status) + " while loading, instantiating or initializing it";
    std::string last;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);)
      if (!line.empty()) last = line;
    if (!last.empty()) why += "; its last words: " + last;
    return why;
  }
  return "";
}

}  // namespace mechsim::tools

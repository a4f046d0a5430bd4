#include "mechsim/cosim/node_end_record.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace mechsim::cosim {

std::string node_end_record_path(const std::string& run_dir, const std::string& node) { return run_dir + "/" + node + ".end"; }

void write_node_end_record(const std::string& run_dir, const std::string& node, const NodeEnd& end) {
  const std::string path = node_end_record_path(run_dir, node), part = path + ".part";
  {
    std::ofstream out(part);
    char line[96];
    std::snprintf(line, sizeof line, "step %llu t %.17g\n", static_cast<unsigned long long>(end.step), end.t);
    out << line;
    if (!out.flush()) throw std::runtime_error("cannot write " + part);
  }
  std::filesystem::rename(part, path);
}

void remove_node_end_record(const std::string& run_dir, const std::string& node) {
  std::error_code ignored;  // absent is the usual case
  std::filesystem::remove(node_end_record_path(run_dir, node), ignored);
}

std::optional<NodeEnd> read_node_end_record(const std::string& run_dir, const std::string& node) {
  if (run_dir.empty()) return std::nullopt;
  std::ifstream in(node_end_record_path(run_dir, node));
  std::string step_word, t_word;
  NodeEnd end;
  if (!(in >> step_word >> end.step >> t_word >> end.t) || step_word != "step" || t_word != "t") return std::nullopt;
  return end;
}

}  // namespace mechsim::cosim

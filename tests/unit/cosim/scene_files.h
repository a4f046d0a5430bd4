// Test helper: scenes written to temporary files, starting from the shipped cam press.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace mechsim::testing {

inline std::string shipped_scene(const std::string& name) {
  return std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/" + name;
}

// Writes `text` to a fresh file and returns its path.
inline std::string write_scene(const std::string& text, const std::string& stem = "scene") {
  static int counter = 0;
  auto dir = std::filesystem::temp_directory_path() / ("mechsim-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  auto path = dir / (stem + std::to_string(counter++) + ".yaml");
  std::ofstream(path) << text;
  return path.string();
}

inline std::string read_file(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The shipped cam press with one line replaced (first occurrence of `from`).
inline std::string cam_press_with(const std::string& from, const std::string& to) {
  std::string text = read_file(shipped_scene("cam_press.yaml"));
  auto pos = text.find(from);
  if (pos == std::string::npos) throw std::runtime_error("cam_press.yaml has no '" + from + "'");
  return text.replace(pos, from.size(), to);
}

}  // namespace mechsim::testing

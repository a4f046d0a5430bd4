#include "scene_snapshot.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace mechsim::bench {

SceneSnapshot::SceneSnapshot(const config::Scene& scene) {
  std::string tmpl = (std::filesystem::temp_directory_path() / "mechsim-scene-XXXXXX").string();
  if (::mkdtemp(tmpl.data()) == nullptr)
    throw std::runtime_error(tmpl + ": cannot create a folder for the scene's copy: " + std::strerror(errno));
  dir_ = tmpl;
  path_ = dir_ + "/" + scene.name + ".yaml";
  std::ofstream out(path_, std::ios::binary);
  out << "# " << scene.file << " as read at the bench's start\n" << config::scene_to_yaml(scene);
  if (!out.flush()) {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
    throw std::runtime_error(path_ + ": cannot write the scene's copy");
  }
}

SceneSnapshot::~SceneSnapshot() {
  std::error_code ec;
  std::filesystem::remove_all(dir_, ec);
}

}  // namespace mechsim::bench

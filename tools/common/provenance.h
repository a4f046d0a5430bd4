// Where a result came from, stored in every JSON the `mechsim` commands write:
//   {"mechsim_version": "0.1.0", "git_commit": "1a2b3c4d5e6f", "scene_file": "scenes/cam.yaml",
//    "scene_sha256": "<64 hex>", "dds": {"cyclonedds": "0.10.2"}, "host": "build-01",
//    "created_utc": "2024-05-01T12:34:56Z"}
// Version and commit are baked in at build time; "dds" lists the vendor libraries this
// build links (a vendor that is not built in is absent).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace mechsim::tools {

// With an empty path, scene_file and scene_sha256 are null. The hash is over the file's
// bytes as stored (overrides from --set are recorded by the caller). Throws
// std::runtime_error naming the path when the scene file cannot be read.
nlohmann::json provenance(const std::string& scene_path_or_empty);

}  // namespace mechsim::tools

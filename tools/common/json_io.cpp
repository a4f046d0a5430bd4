#include "json_io.h"

#include <cmath>

#include "atomic_file.h"

namespace mechsim::tools {

void write_json_file(const std::string& path, const nlohmann::json& document) {
  const std::string text =
      document.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  write_file_atomically(path, text);
}

nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace mechsim::tools

// JSON results of the `mechsim` commands: every document carries `schema_version` (this
// constant) and `provenance` (provenance.h); layouts are documented in docs/.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace mechsim::tools {

// Bumped when a JSON layout changes incompatibly.
inline const std::string schema_version = "1";

// Writes `document` pretty-printed (2-space indent, trailing newline), atomically.
// NaN and infinite numbers come out as null (JSON has no such numbers); invalid UTF-8
// in strings is replaced rather than refused. Throws std::runtime_error naming the path.
void write_json_file(const std::string& path, const nlohmann::json& document);

// A finite number as itself, NaN or an infinity as null.
nlohmann::json finite_or_null(double v);

}  // namespace mechsim::tools

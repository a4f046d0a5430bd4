// SHA-256 of a byte string, for provenance (the scene file hash in every JSON result).
#pragma once

#include <string>
#include <string_view>

namespace mechsim::config {

// Lower-case hex digest (64 characters) as in `sha256sum`.
std::string sha256_hex(std::string_view bytes);

}  // namespace mechsim::config

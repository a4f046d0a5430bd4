// printf-style formatting into a std::string, for the reports' and plots' numbers: one
// definition instead of a file-local copy per analysis (which kept them out of the unity
// build). The format attribute lets the compiler check each call's arguments.
#pragma once

#include <string>

namespace mechsim::tools {

// std::snprintf(format, ...) as a string, as long as it needs to be.
[[gnu::format(printf, 1, 2)]] std::string fmt(const char* format, ...);

}  // namespace mechsim::tools

// The MCAP schema of a mechsim type: encoding "omgidl", data = a self-contained IDL text
// (idl/header.idl followed by the type's own file, without the #include and include-guard
// lines, so that a reader needs no other file to parse it).
#pragma once

#include <map>
#include <string>

#include "cdr_decoder.h"

namespace mechsim::recorder {

// idl/*.idl as compiled in: file name ("cam.idl") -> text.
const std::map<std::string, std::string>& idl_files();

// The schema text of `layout`'s type. Throws std::logic_error when its IDL file was not
// compiled in (a layout and idl/CMakeLists.txt out of step).
std::string schema_text(const MessageLayout& layout);

}  // namespace mechsim::recorder

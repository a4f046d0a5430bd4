// The MCAP schema of a mechsim type: encoding "omgidl", data = a self-contained IDL text
// (idl/header.idl followed by the type's own file, without the #include and include-guard
// lines, so that a reader needs no other file to parse it).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "cdr_decoder.h"

namespace mechsim::recorder {

// idl/*.idl as compiled in: file name ("cam.idl") -> text.
const std::map<std::string, std::string>& idl_files();

// The members of `struct <name>` in an IDL text, in order, after its leading
// `Header header;` (which every mechsim type has and the decoder reads separately).
// Understands the scalar types of cdr_decoder.h and (bounded) strings; throws
// std::logic_error naming the member for anything else (a sequence, a nested struct) or
// when the struct or its Header is missing.
std::vector<CdrField> struct_members(const std::string& idl_text, const std::string& name);

// The schema text of `layout`'s type. Throws std::logic_error when its IDL file was not
// compiled in (a layout and idl/CMakeLists.txt out of step).
std::string schema_text(const MessageLayout& layout);

}  // namespace mechsim::recorder

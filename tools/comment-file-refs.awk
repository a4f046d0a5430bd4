# For tools/check-doc-links.sh: prints "file:line:path" for every file a code comment names
# as a path from the repository root (docs/, libs/, tools/, nodes/, tests/, idl/, config/,
# cmake/) or from the comment's own library folder (src/, include/), with a slash and a
# known extension. The comment is what follows // in C, C++ and IDL, # in CMake and shell.
# Bare names (node_endpoints.cpp) and short forms (transport/raw.h, spec/cam.md) are left
# alone: where they point depends on the reader's context.
BEGIN {
  ext = "(md|h|hpp|c|cc|cpp|idl|sh|yaml|yml|xml|json|txt|cmake|py|awk)"
  path = "[A-Za-z0-9_.+-]*(/[A-Za-z0-9_.+-]+)+\\." ext
}
{
  if (FILENAME ~ /\.(h|hpp|c|cc|cpp|idl)$/) marker = "//"
  else marker = "#"
  i = index($0, marker)
  if (i == 0) next
  c = substr($0, i + length(marker))
  while (match(c, path)) {
    ref = substr(c, RSTART, RLENGTH)
    before = RSTART > 1 ? substr(c, RSTART - 1, 1) : ""
    after = substr(c, RSTART + RLENGTH, 1)
    c = substr(c, RSTART + RLENGTH)
    # Part of a longer name (x.md5), an absolute path, a URL, or a placeholder (<dir>/x.xml).
    if (after ~ /[A-Za-z0-9_]/ || before ~ /[\/:~$<>{}*]/) continue
    if (ref ~ /^(docs|libs|tools|nodes|tests|idl|config|cmake|src|include)\//) print FILENAME ":" FNR ":" ref
  }
}

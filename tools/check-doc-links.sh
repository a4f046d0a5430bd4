#!/usr/bin/env bash
# Checks that README.md and docs/**/*.md link only files of this repository: every relative
# markdown link [text](target) must exist (anchors after '#' are ignored, http(s) and
# mailto links are not checked), and no page may point outside the tree ("../shared/" and
# the like: a clone holds nothing there). And that every file a code comment names by its
# path exists (tools/comment-file-refs.awk says which references count). Prints file:line
# and the missing target for each bad one; exit 1 if there is one. Run by ctest (doc_links,
# label unit).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
bad=0
while IFS= read -r page; do
  dir=$(dirname "$page")
  # Markdown links, as "line:](target)", several per line.
  while IFS=: read -r lineno match; do
    target="${match#](}"
    target="${target%)}"
    case "$target" in ""|http://*|https://*|mailto:*|\#*) continue ;; esac
    path="${target%%#*}"
    path="${path%% *}"  # [x](file "title")
    if [ ! -e "$dir/$path" ]; then
      echo "$page:$lineno: link to a missing file: $target"
      bad=1
    elif [[ "$(realpath -m "$dir/$path")" != "$root"* ]]; then
      echo "$page:$lineno: link leaves the repository: $target"
      bad=1
    fi
  done < <(grep -no '\]([^)]*)' "$page" || true)
  # Paths outside the tree written as code, e.g. `../shared/DESIGN.md`.
  while IFS=: read -r lineno match; do
    echo "$page:$lineno: names a file outside the repository: $match"
    bad=1
  done < <(grep -no '`\.\./[^`]*`' "$page" || true)
done < <(find README.md docs -name '*.md' | sort)
# Files named in code comments: from the root, or src/... and include/... from the
# commenting file's own library folder (the nearest enclosing folder that has the path).
checked=0
while IFS=: read -r file lineno ref; do
  checked=$((checked + 1))
  case "$ref" in
    src/*|include/*)
      dir=$(dirname "$file")
      while [ "$dir" != . ] && [ ! -e "$dir/$ref" ]; do dir=$(dirname "$dir"); done
      [ "$dir" != . ] && continue ;;
    *) [ -e "$ref" ] && continue ;;
  esac
  echo "$file:$lineno: a comment names a missing file: $ref"
  bad=1
done < <(find CMakeLists.txt cmake idl libs nodes tests tools -type f \
           \( -name '*.h' -o -name '*.hpp' -o -name '*.c' -o -name '*.cc' -o -name '*.cpp' -o -name '*.idl' \
              -o -name CMakeLists.txt -o -name '*.cmake' -o -name '*.sh' \) -print0 |
         sort -z | xargs -0 awk -f tools/comment-file-refs.awk)
[ "$bad" = 0 ] && echo "doc links: every link of README.md and docs/ points into the repository;" \
  "the $checked file references of code comments name files that exist"
exit "$bad"

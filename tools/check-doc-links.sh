#!/usr/bin/env bash
# Checks that README.md and docs/**/*.md link only files of this repository: every relative
# markdown link [text](target) must exist (anchors after '#' are ignored, http(s) and
# mailto links are not checked), and no page may point outside the tree ("../shared/" and
# the like: a clone holds nothing there). Prints file:line and the missing target for each
# bad link; exit 1 if there is one. Run by ctest (doc_links, label unit).
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
[ "$bad" = 0 ] && echo "doc links: every link of README.md and docs/ points into the repository"
exit "$bad"

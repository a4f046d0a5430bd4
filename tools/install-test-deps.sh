#!/usr/bin/env bash
# Installs what the test suite needs beyond the Debian packages: the @mcap/core npm reader
# the MCAP tests run (tests/integration/mcap_reader: package.json, package-lock.json,
# read_mcap.mjs), pinned by its lock file, into BUILD_DIR/mcap-reader (default build/).
# Needs the npm registry once per build tree; does nothing when the installed lock file is
# the current one. Called by tools/run-tests.sh. Without node/npm it says so and exits 0
# (the reader tests then skip, saying why).
#   tools/install-test-deps.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
src=tests/integration/mcap_reader
work="$build/mcap-reader"
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  echo "install-test-deps: node/npm not installed: the third-party MCAP reader tests will be skipped"
  exit 0
fi
mkdir -p "$work"
cp "$src/package.json" "$src/package-lock.json" "$src/read_mcap.mjs" "$work/"
if [ -d "$work/node_modules/@mcap/core" ] && cmp -s "$src/package-lock.json" "$work/.installed-package-lock.json"; then
  exit 0
fi
echo "install-test-deps: npm ci in $work (@mcap/core, pinned by $src/package-lock.json)"
# Few retries: without registry access this fails in seconds, not minutes.
if (cd "$work" && npm ci --ignore-scripts --no-audit --no-fund --fetch-retries=1 --fetch-retry-mintimeout=2000 \
      --fetch-retry-maxtimeout=5000 --fetch-timeout=30000 > npm-ci.log 2>&1); then
  cp "$src/package-lock.json" "$work/.installed-package-lock.json"
else
  echo "install-test-deps: npm ci failed (no access to the npm registry?): see $work/npm-ci.log;" \
       "the MCAP reader tests will fail until this succeeds" >&2
  tail -3 "$work/npm-ci.log" >&2 || true
fi

#!/usr/bin/env bash
# Installs what the test suite needs beyond the Debian packages, pinned by lock files:
#   - the @mcap/core npm reader the MCAP tests run (tests/integration/mcap_reader:
#     package.json, package-lock.json, read_mcap.mjs) into BUILD_DIR/mcap-reader;
#   - the Foxglove WebSocket protocol's client and OMG IDL deserializer the live-server tests
#     run (tests/integration/live_client: @foxglove/ws-protocol, ws, watch_live.mjs) into
#     BUILD_DIR/live-client.
# BUILD_DIR defaults to build/. Needs the npm registry once per build tree; does nothing when
# the installed lock file is the current one. Called by tools/run-tests.sh. Without node/npm
# it says so and exits 0 (those tests then skip, saying why).
#   tools/install-test-deps.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  echo "install-test-deps: node/npm not installed: the third-party MCAP reader and Foxglove client tests will be skipped"
  exit 0
fi

# install SOURCE_DIR WORK_DIR MARKER_PACKAGE WHAT FILE...: npm ci of SOURCE_DIR's lock file
# into WORK_DIR, with FILE... copied next to it.
install() {
  local src=$1 work=$2 marker=$3 what=$4
  shift 4
  mkdir -p "$work"
  cp "$src/package.json" "$src/package-lock.json" "$@" "$work/"
  if [ -d "$work/node_modules/$marker" ] && cmp -s "$src/package-lock.json" "$work/.installed-package-lock.json"; then
    return 0
  fi
  echo "install-test-deps: npm ci in $work ($what, pinned by $src/package-lock.json)"
  # Few retries: without registry access this fails in seconds, not minutes.
  if (cd "$work" && npm ci --ignore-scripts --no-audit --no-fund --fetch-retries=1 --fetch-retry-mintimeout=2000 \
        --fetch-retry-maxtimeout=5000 --fetch-timeout=30000 > npm-ci.log 2>&1); then
    cp "$src/package-lock.json" "$work/.installed-package-lock.json"
  else
    echo "install-test-deps: npm ci failed (no access to the npm registry?): see $work/npm-ci.log;" \
         "the tests that need $what will fail until this succeeds" >&2
    tail -3 "$work/npm-ci.log" >&2 || true
  fi
}

install tests/integration/mcap_reader "$build/mcap-reader" @mcap/core "@mcap/core" tests/integration/mcap_reader/read_mcap.mjs
install tests/integration/live_client "$build/live-client" @foxglove/ws-protocol "@foxglove/ws-protocol" \
  tests/integration/live_client/watch_live.mjs

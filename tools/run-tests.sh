#!/usr/bin/env bash
# README command 2: builds and runs the whole default test suite (unit + integration,
# GoogleTest under ctest). Longer sweeps have their own labels: see docs/testing.md.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-deps.sh --tests
tools/build.sh
tools/install-test-deps.sh  # the npm MCAP reader, once per build tree (the tests never fetch)
exec ctest --test-dir build -L '^(unit|integration)$' -j2 --output-on-failure --timeout 600 "$@"

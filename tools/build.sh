#!/usr/bin/env bash
# Configures and builds mechsim into build/ (executables in build/bin/, tests in build/tests/).
#   tools/build.sh             everything, with the test suites (README command 2)
#   tools/build.sh --run-only  only `mechsim` and the node executables, what a run needs
#                              (README command 1: the first result does not wait for ~100
#                              test executables); a tree configured with tests keeps them
set -euo pipefail
cd "$(dirname "$0")/.."
targets=()
tests=ON
case "${1:-}" in
  "") ;;
  --run-only)
    targets=(--target mechsim mechsim_nodes)
    # A new tree is configured without the suites (GoogleTest need not be installed yet);
    # an existing one keeps what it has, so that the test command's build stays valid.
    tests=$(sed -n 's/^MECHSIM_BUILD_TESTS:BOOL=//p' build/CMakeCache.txt 2>/dev/null || true)
    tests=${tests:-OFF}
    ;;
  *) echo "usage: tools/build.sh [--run-only]" >&2; exit 2 ;;
esac
# ccache, when installed, makes rebuilds after a pull cheap; the build does not need it.
options=()
if command -v ccache >/dev/null; then options+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
# Ninja (Debian package ninja-build) for a new tree: it starts a library's users' sources while
# the library's last ones still compile, where make waits for the library, so neither core
# idles behind a long unit. An existing tree keeps its generator (cmake cannot change it).
if [ ! -f build/CMakeCache.txt ] && command -v ninja >/dev/null; then options+=(-G Ninja); fi
# Unity batches: a build from scratch parses the heavy headers once per batch, not per file
# (CMakeLists.txt, MECHSIM_UNITY_BUILD; the test suites stay file by file).
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DMECHSIM_BUILD_TESTS=$tests" -DMECHSIM_UNITY_BUILD=ON "${options[@]}" >/dev/null
cmake --build build -j"$(nproc)" "${targets[@]}"

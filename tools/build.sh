#!/usr/bin/env bash
# Configures and builds mechsim into build/ (executables in build/bin/).
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache, when installed, makes rebuilds after a pull cheap; the build does not need it.
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" >/dev/null
cmake --build build -j"$(nproc)"

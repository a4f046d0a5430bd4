#!/usr/bin/env bash
# README command 1: from a fresh Debian 12 machine to a running main job.
# Installs the packages a run needs, builds mechsim and the node executables only (the test
# suites are the second command's), and launches the default scene (the cam press).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-deps.sh
tools/build.sh --run-only
exec build/bin/mechsim launch config/scenes/cam_press.yaml "$@"

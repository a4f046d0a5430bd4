#!/usr/bin/env bash
# The cost of a study (docs/sweeps.md, "What it costs"), on this machine, same minute:
#  1. a 64-point grid of cam_press (spring stiffness x preload, 8 x 8) as `mechsim sweep
#     --jobs 2` against the same 64 points run one after the other with `mechsim launch`;
#  2. one run of nc_slide_loop from Python in process (mechsim.run) against `mechsim launch`
#     of it (the fastest of 3 each).
# Needs a built tree (tools/build.sh) with the Python package (pybind11-dev).
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=build/bin/mechsim
work=$(mktemp -d /tmp/mechsim-bench-sweep-XXXXXX)
trap 'rm -rf "$work"' EXIT
python=/usr/bin/python3; [ -x $python ] || python=python3

PYTHONPATH=build/python $python - "$bin" "$work" <<'PY'
import json, os, subprocess, sys, time
import mechsim

bin, work = sys.argv[1], sys.argv[2]
quiet = dict(stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)

scene = "config/scenes/cam_press.yaml"
t0 = time.perf_counter()
subprocess.run([bin, "sweep", scene, "--vary", "follower.spring.stiffness=5..13 N/mm:8",
                "--vary", "follower.spring.preload=60..130 N:8", "--jobs", "2", "--out", work + "/sweep",
                "--no-plot", "--no-progress"], **quiet)
sweep_s = time.perf_counter() - t0
rows = json.load(open(work + "/sweep/sweep.json"))["rows"]
t0 = time.perf_counter()
for r in rows:
    subprocess.run([bin, "launch", scene, "--set", "follower.spring.stiffness=" + r["follower.spring.stiffness.text"],
                    "--set", "follower.spring.preload=" + r["follower.spring.preload.text"], "--runs-dir", work + "/runs",
                    "--no-plot", "--no-progress"], **quiet)
launch_s = time.perf_counter() - t0
print(f"{len(rows)}-point grid of {scene}: sweep --jobs 2 {sweep_s:.2f} s, {len(rows)} x launch one after the other "
      f"{launch_s:.2f} s: {launch_s / sweep_s:.1f}x faster")

scene = "config/scenes/nc_slide_loop.yaml"
best_launch = best_python = float("inf")
for _ in range(3):
    t0 = time.perf_counter()
    subprocess.run([bin, "launch", scene, "--runs-dir", work + "/runs", "--no-plot", "--no-progress"], **quiet)
    best_launch = min(best_launch, time.perf_counter() - t0)
    t0 = time.perf_counter()
    r = mechsim.run(scene, run_dir=work + "/python")
    best_python = min(best_python, time.perf_counter() - t0)
    assert r.ok, r.reason
print(f"{scene}: mechsim.run (Python, in process) {best_python:.2f} s, mechsim launch {best_launch:.2f} s "
      f"(fastest of 3 each): {best_python / best_launch:.2f}x the launch wall time")
PY

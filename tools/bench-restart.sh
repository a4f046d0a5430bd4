#!/usr/bin/env bash
# Restart with rollback (docs/faults.md), measured:
#  1. what checkpointing costs: steps/s of a scene with `faults.restart: on_failure` (every
#     node checkpoints every faults.checkpoint_every steps, default 1000) against the same
#     scene without, alternating, in the same minute; medians;
#  2. how long a kill stops the run: a node SIGKILLed mid-run, the launcher's summary
#     (restart.restarts[]) gives the time from seeing the death to the resume command and
#     to every node stepping past the checkpoint again; medians.
#   tools/bench-restart.sh [RUNS=5] [SCENE=config/scenes/nc_slide_loop_1ms.yaml] [END=20 s] [NODE=slide] [PART=both|cost|kill]
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
scene=${2:-config/scenes/nc_slide_loop_1ms.yaml}
end=${3:-20 s}
node=${4:-slide}
part=${5:-both}
mechsim=build/bin/mechsim
tmp=$(mktemp -d)
launcher=""
cleanup() {
  if [ -n "$launcher" ]; then kill "$launcher" 2>/dev/null || true; wait "$launcher" 2>/dev/null || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT
field() { python3 -c "import json,sys;d=json.load(open(sys.argv[1]));print(eval(sys.argv[2]))" "$1" "$2"; }
median() { printf "%s\n" "$@" | sort -g | awk '{a[NR]=$1} END {print (NR ? a[int((NR+1)/2)] : "n/a")}'; }

echo "scene $scene, --end '$end', $runs runs each"
plain=(); ckpt=()
[ "$part" = kill ] && runs_cost=0 || runs_cost=$runs
for i in $(seq "$runs_cost"); do
  "$mechsim" launch "$scene" --end "$end" --no-plot --no-progress --runs-dir "$tmp/runs" --json "$tmp/p.json" >/dev/null 2>&1
  plain+=("$(field "$tmp/p.json" "d['steps_per_second']")")
  "$mechsim" launch "$scene" --end "$end" --set faults.restart=on_failure --no-plot --no-progress --runs-dir "$tmp/runs" \
    --json "$tmp/c.json" >/dev/null 2>&1
  ckpt+=("$(field "$tmp/c.json" "d['steps_per_second']")")
  echo "run $i: without checkpoints ${plain[-1]} steps/s, checkpoint every $(field "$tmp/c.json" "d['restart']['checkpoint_every']") steps ${ckpt[-1]} steps/s"
  rm -rf "$tmp/runs"
done
if [ "$runs_cost" -gt 0 ]; then
  mp=$(median "${plain[@]}"); mc=$(median "${ckpt[@]}")
  echo "median: without $mp steps/s, with checkpoints $mc steps/s, ratio $(python3 -c "print(f'{$mc/$mp:.3f}')")"
fi
[ "$part" = cost ] && exit 0

# 2. A kill of NODE once its output log holds 400 kB (some thousand steps in).
resume=(); stepping=()
for i in $(seq "$runs"); do
  "$mechsim" launch "$scene" --end "$end" --set faults.restart=on_failure --no-plot --no-progress --runs-dir "$tmp/k" \
    --json "$tmp/k.json" >"$tmp/k.log" 2>&1 &
  launcher=$!
  run=""
  for _ in $(seq 3000); do run=$(ls -d "$tmp"/k/*/ 2>/dev/null | head -1 || true); run=${run%/}; [ -n "$run" ] && [ -f "$run/$node.outputs.bin" ] && break; sleep 0.01; done
  # The pid of NODE of this run: its command line names the run folder.
  pid=""
  for _ in $(seq 3000); do
    size=$(stat -c %s "$run/$node.outputs.bin" 2>/dev/null || echo 0)
    if [ "$size" -gt 400000 ]; then
      pid=$(for p in /proc/[0-9]*; do
              c=$( { tr '\0' ' ' < "$p/cmdline"; } 2>/dev/null || true)
              case "$c" in *"--node $node --run-id"*"$run"*) basename "$p";; esac
            done | head -1 || true)
      [ -n "$pid" ] && break
    fi
    sleep 0.01
  done
  if [ -z "$pid" ]; then echo "run $i: node $node not found"; wait "$launcher" || true; launcher=""; continue; fi
  kill -9 "$pid"
  wait "$launcher" || true
  launcher=""
  resume+=("$(field "$tmp/k.json" "d['restart']['restarts'][0]['kill_to_resume_s']")")
  stepping+=("$(field "$tmp/k.json" "d['restart']['restarts'][0]['kill_to_stepping_s']")")
  echo "run $i: killed $node at step $(field "$tmp/k.json" "d['restart']['restarts'][0]['last_step']"), back to $(field "$tmp/k.json" "d['restart']['restarts'][0]['rollback_step']"): resume sent after ${resume[-1]} s, stepping after ${stepping[-1]} s (status $(field "$tmp/k.json" "d['status']"))"
  rm -rf "$tmp/k"
done
echo "median: kill -> resume $(median "${resume[@]}") s, kill -> stepping again $(median "${stepping[@]}") s"

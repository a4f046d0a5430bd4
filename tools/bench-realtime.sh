#!/usr/bin/env bash
# Real-time benchmark (docs/realtime.md): the shipped real-time scenes paced at rtf 1 for
# END of simulated time (default 60 s), then the highest real-time factor each sustains
# with no missed deadline (doubling, then bisection, runs of about TRIAL_WALL s of wall time).
#   tools/bench-realtime.sh [--end '60 s'] [--trial-wall 8] [--no-sweep] [--no-floor] [--json FILE] [SCENE ...]
# First it measures the machine's own floor: cyclictest (rt-tests) at the scenes' priority,
# 1 ms period, for the same wall time: the wake-up latency any sleeping thread sees here.
# Default scenes: nc_slide_loop_rt cam_press_rt. Needs the scenes' rights (root, or
# CAP_SYS_NICE + CAP_IPC_LOCK); runs on an otherwise idle machine tell the truth, runs next
# to a build do not. Prints a table; --json writes every figure.
set -euo pipefail
cd "$(dirname "$0")/.."
end="60 s"
trial_wall=8
sweep=1
floor=1
json_out=""
scenes=()
while [ $# -gt 0 ]; do
  case "$1" in
    --end) end="$2"; shift 2 ;;
    --trial-wall) trial_wall="$2"; shift 2 ;;
    --no-sweep) sweep=0; shift ;;
    --no-floor) floor=0; shift ;;
    --json) json_out="$2"; shift 2 ;;
    -h|--help) sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) scenes+=("$1"); shift ;;
  esac
done
[ ${#scenes[@]} -gt 0 ] || scenes=(nc_slide_loop_rt cam_press_rt)
command -v python3 >/dev/null || { echo "bench-realtime: needs python3 to read the run summaries (apt-get install python3)" >&2; exit 2; }
[ -x build/bin/mechsim ] || { echo "bench-realtime: build first (tools/build.sh)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# run SCENE RTF END TAG -> prints "missed p99_ms max_ms jitter_std_ms jitter_max_ms rtf_achieved ok"
run() {
  local scene=$1 rtf=$2 end=$3 tag=$4
  local rc=0
  build/bin/mechsim launch "config/scenes/$scene.yaml" --rtf "$rtf" --end "$end" --no-progress \
    --runs-dir "$tmp/runs" --json "$tmp/$tag.json" > "$tmp/$tag.log" 2>&1 || rc=$?
  if [ ! -s "$tmp/$tag.json" ]; then echo "bench-realtime: $scene at rtf $rtf failed (exit $rc):" >&2; tail -5 "$tmp/$tag.log" >&2; return 1; fi
  python3 - "$tmp/$tag.json" "$rc" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); r = s["realtime"]
print(r["missed_deadlines"], 1e3 * r["lateness_p99_s"], 1e3 * r["lateness_max_s"], 1e3 * r["period_jitter_std_s"],
      1e3 * r["period_jitter_max_s"], r["rtf_achieved"], "ok" if sys.argv[2] == "0" else "failed")
PY
}

if [ "$floor" = 1 ]; then
  if command -v cyclictest >/dev/null; then
    secs=$(python3 -c "print(int(float('$end'.split()[0])))")
    cyclictest -m -p 50 -i 1000 -t 1 -D "$secs" -q --histogram=30000 --histfile="$tmp/cyclictest.hist" >/dev/null 2>&1 || true
    python3 - "$tmp/cyclictest.hist" "$secs" <<'PY'
import sys
rows = [tuple(int(x) for x in l.split()[:2]) for l in open(sys.argv[1]) if l.strip() and not l.startswith("#")]
n = sum(c for _, c in rows)
def q(p):
    t = 0
    for lat, c in rows:
        t += c
        if t >= p * n: return lat
mx = max((lat for lat, c in rows if c), default=0)
over = [l for l in open(sys.argv[1]) if l.startswith("# Max Latencies")]
print(f"machine floor (cyclictest, SCHED_FIFO 50, mlockall, 1 ms period, {sys.argv[2]} s): {n} wake-ups, "
      f"median {q(0.5)} us, p99 {q(0.99)} us, p99.9 {q(0.999)} us, {over[0].split(':')[1].strip() if over else mx} us max, "
      f"{sum(c for lat, c in rows if lat >= 1000)} of them >= 1 ms")
PY
  else
    echo "machine floor: cyclictest not installed (apt-get install rt-tests); skipped"
  fi
fi

results="$tmp/results.jsonl"
: > "$results"
printf '%-18s %8s %7s %9s %9s %10s %10s %9s\n' scene rtf missed "p99 [ms]" "max [ms]" "jit σ[ms]" "jit max" "rtf got"
for scene in "${scenes[@]}"; do
  read -r missed p99 max jstd jmax got status < <(run "$scene" 1 "$end" "$scene-rtf1")
  printf '%-18s %8s %7s %9.3f %9.3f %10.3f %10.3f %9.4f %s\n' "$scene" 1 "$missed" "$p99" "$max" "$jstd" "$jmax" "$got" "$status"
  # The node of the worst lateness and its figures, to say where the outliers are.
  python3 - "$tmp/$scene-rtf1.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["realtime"]["nodes"]
for n, f in r.items():
    print(f"    {n:12s} {f['publications']} publications, {f['missed_deadlines']} missed, median {1e3*f['lateness_median_s']:.3f} ms, "
          f"p99 {1e3*f['lateness_p99_s']:.3f} ms, max {1e3*f['lateness_max_s']:.3f} ms, jitter {1e3*f['period_jitter_std_s']:.3f} ms std")
# The worst publications: the same step late on every node is one stall travelling around the ring.
steps = {}
for n, f in r.items():
    for w in f.get("worst", []):
        steps.setdefault(w["step"], []).append((n, w["lateness_s"]))
worst = sorted(steps.items(), key=lambda kv: -max(l for _, l in kv[1]))[:5]
print("    worst publications: " + "; ".join(f"step {k}: " + ", ".join(f"{n} {1e3*l:.2f} ms" for n, l in v) for k, v in worst))
PY
  best=""
  if [ "$sweep" = 1 ]; then
    # From rtf 1: doubling up while no deadline is missed, or halving down (to 1/16) while
    # some are; then 4 bisection steps between the last good and the first bad factor.
    try() {  # try RTF -> 0 when the trial missed no deadline
      local r=$1 sim out
      sim=$(python3 -c "print(f'{$r * $trial_wall:g} s')")
      out=$(run "$scene" "$r" "$sim" "$scene-rtf$r") || out="failed"
      echo "      rtf $r: $out" >&2
      [ "$(echo "$out" | awk '{print $1}')" = 0 ]
    }
    good=""; bad=""
    if [ "$missed" = 0 ]; then
      good=1; rtf=2
      while [ -z "$bad" ] && python3 -c "import sys; sys.exit(0 if $rtf <= 1024 else 1)"; do
        if try "$rtf"; then good=$rtf; rtf=$(python3 -c "print($rtf * 2)"); else bad=$rtf; fi
      done
    else
      bad=1; rtf=0.5
      while [ -z "$good" ] && python3 -c "import sys; sys.exit(0 if $rtf >= 1/16 else 1)"; do
        if try "$rtf"; then good=$rtf; else bad=$rtf; rtf=$(python3 -c "print($rtf / 2)"); fi
      done
    fi
    if [ -n "$good" ] && [ -n "$bad" ]; then
      for _ in 1 2 3 4; do
        mid=$(python3 -c "print(round(($good + $bad) / 2, 3))")
        if try "$mid"; then good=$mid; else bad=$mid; fi
      done
    fi
    best=$good
    if [ -n "$best" ]; then
      echo "    highest rtf with no missed deadline: $best (first miss at ${bad:-none up to 1024}, ${trial_wall} s wall per trial)"
    else
      echo "    no rtf down to 1/16 without a missed deadline (${trial_wall} s wall per trial): the misses are machine stalls, not load"
    fi
  fi
  python3 - "$tmp/$scene-rtf1.json" "$scene" "$end" "$best" >> "$results" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
print(json.dumps({"scene": sys.argv[2], "end": sys.argv[3], "realtime": s["realtime"] | {"nodes": {n: {k: v for k, v in f.items() if k != "lateness_histogram"} for n, f in s["realtime"]["nodes"].items()}},
                  "process_realtime": s.get("process_realtime", {}), "highest_rtf_without_miss": float(sys.argv[4]) if sys.argv[4] else None}))
PY
done
[ -z "$json_out" ] || python3 -c "import json,sys; json.dump([json.loads(l) for l in open('$results')], open('$json_out','w'), indent=1)"

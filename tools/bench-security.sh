#!/usr/bin/env bash
# What DDS Security costs (docs/security.md): nc_slide_loop (3 nodes + launcher, 20 000
# lock-step steps) unsecured, secured with `dds.protection: sign` and secured with
# `encrypt` (the default), per vendor layout, the variants taking turns inside every
# repetition so the machine's load falls on all alike; prints the medians (and range) as a
# Markdown table.
#   tools/bench-security.sh [RUNS] [BUILD_DIR] [LAYOUTS]     e.g. tools/bench-security.sh 5 build "cyclone fastdds"
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
build=${2:-build}
layouts=${3:-cyclone fastdds}
mechsim="$build/bin/mechsim"
scene=config/scenes/nc_slide_loop.yaml
[ -x "$mechsim" ] || { echo "bench-security: $mechsim is missing (build first, or pass the build folder)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset CYCLONEDDS_URI FASTRTPS_DEFAULT_PROFILES_FILE MECHSIM_DDS_SECURITY MECHSIM_DDS_IDENTITY
"$mechsim" security init "$tmp/sec" "$scene" > "$tmp/init.log" 2>&1 || { cat "$tmp/init.log" >&2; exit 1; }

: > "$tmp/results"
for i in $(seq "$runs"); do
  for layout in $layouts; do
    for variant in unsecured sign encrypt; do
      extra=()
      [ "$variant" != unsecured ] && extra=(--set "dds.security=$tmp/sec" --set "dds.protection=$variant")
      rate=failed cpu=failed
      # CPU seconds of the launcher and its nodes (its children), next to the pace: the pace
      # swings with the machine's load, the CPU a step costs much less.
      if python3 - "$tmp/cpu" "$mechsim" launch "$scene" --end "0.5 s" --dds "$layout" "${extra[@]}" --no-plot --no-progress \
           --runs-dir "$tmp/runs" --json "$tmp/s.json" > "$tmp/launch.log" 2>&1 <<'PY'
import resource, subprocess, sys
rc = subprocess.call(sys.argv[2:])
r = resource.getrusage(resource.RUSAGE_CHILDREN)
open(sys.argv[1], "w").write(f"{r.ru_utime + r.ru_stime}\n")
sys.exit(rc)
PY
      then
        rate=$(python3 -c "import json;print(round(json.load(open('$tmp/s.json'))['steps_per_second']))")
        # CPU microseconds per lock-step step, all processes together (20 000 steps).
        cpu=$(python3 -c "print(round(float(open('$tmp/cpu').read()) / 20000 * 1e6))")
      else
        echo "run $i: $layout $variant failed:" >&2
        tail -n 5 "$tmp/launch.log" >&2
      fi
      rm -rf "$tmp/runs"
      printf '%s\t%s\t%s\t%s\n' "$layout" "$variant" "$rate" "$cpu" >> "$tmp/results"
      echo "run $i: $layout $variant: $rate steps/s, $cpu us CPU per step" >&2
    done
  done
done

python3 - "$tmp/results" "$runs" <<'PY'
import statistics, sys
path, runs = sys.argv[1], sys.argv[2]
rates, cpus = {}, {}
for line in open(path):
    layout, variant, rate, cpu = line.rstrip("\n").split("\t")
    rates.setdefault(layout, {}).setdefault(variant, []).append(rate)
    cpus.setdefault(layout, {}).setdefault(variant, []).append(cpu)
def cell(values):
    ok = sorted(float(r) for r in values if r != "failed")
    failed = sum(r == "failed" for r in values)
    text = f"{statistics.median(ok):.0f} ({ok[0]:.0f}-{ok[-1]:.0f})" if ok else "-"
    return (text + (f", {failed} failed" if failed else "")), (statistics.median(ok) if ok else None)
def table(title, values):
    print(title + "\n")
    print("| layout | unsecured | sign | encrypt | sign / unsecured | encrypt / unsecured | encrypt / sign |")
    print("|---|---|---|---|---|---|---|")
    ratio = lambda a, b: f"{a / b:.2f}" if a and b else "-"
    for layout, by in values.items():
        (u, um), (s, sm), (e, em) = (cell(by.get(v, [])) for v in ("unsecured", "sign", "encrypt"))
        print(f"| {layout} | {u} | {s} | {e} | {ratio(sm, um)} | {ratio(em, um)} | {ratio(em, sm)} |")
table(f"nc_slide_loop, steps per second, median of {runs} (min-max); 20 000 lock-step steps per run", rates)
table(f"\nCPU microseconds per step, launcher and nodes together, median of {runs} (min-max)", cpus)
PY

#!/usr/bin/env bash
# Lock-step rate of the shipped scenes on every DDS vendor layout: all nodes (and the
# launcher) on Cyclone DDS, all on Fast DDS over shared memory, all on Fast DDS over UDP
# loopback, and mixed (alternating vendors; Cyclone <-> Fast DDS always over UDP). Measured
# in one go: the layouts take turns inside every repetition, so the machine's load falls on
# all of them alike; prints the medians (and the range) as a Markdown table for docs/dds.md.
#   tools/bench-vendors.sh [RUNS] [BUILD_DIR]      e.g. tools/bench-vendors.sh 5 build
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
build=${2:-build}
mechsim="$build/bin/mechsim"
[ -x "$mechsim" ] || { echo "bench-vendors: $mechsim is missing (build first, or pass the build folder)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset CYCLONEDDS_URI FASTRTPS_DEFAULT_PROFILES_FILE  # the launcher's loopback profiles

# scene file | end time (20 000 steps each)
scenes=("config/scenes/cam_press.yaml|20 s" "config/scenes/nc_slide_loop.yaml|0.5 s")
# column | --dds | MECHSIM_FASTDDS_TRANSPORT
layouts=("Cyclone|cyclone|shm" "Fast DDS (shm)|fastdds|shm" "Fast DDS (UDP)|fastdds|udp" "mixed|mixed|shm")

: > "$tmp/results"
for i in $(seq "$runs"); do
  for s in "${scenes[@]}"; do
    scene=${s%%|*}
    end=${s#*|}
    for l in "${layouts[@]}"; do
      IFS='|' read -r column dds transport <<< "$l"
      rate=failed
      if MECHSIM_FASTDDS_TRANSPORT=$transport "$mechsim" launch "$scene" --end "$end" --dds "$dds" --no-plot \
           --no-progress --runs-dir "$tmp/runs" --json "$tmp/s.json" > "$tmp/launch.log" 2>&1; then
        rate=$(python3 -c "import json;print(round(json.load(open('$tmp/s.json'))['steps_per_second']))")
      else
        echo "run $i: $(basename "$scene") on $column failed: $(tail -n 2 "$tmp/launch.log" | head -n 1)" >&2
      fi
      rm -rf "$tmp/runs"
      printf '%s\t%s\t%s\n' "$(basename "$scene" .yaml)" "$column" "$rate" >> "$tmp/results"
      echo "run $i: $(basename "$scene" .yaml) on $column: $rate steps/s" >&2
    done
  done
done

python3 - "$tmp/results" "$runs" "${layouts[@]}" <<'PY'
import statistics, sys
path, runs, columns = sys.argv[1], sys.argv[2], [l.split("|")[0] for l in sys.argv[3:]]
rates = {}
for line in open(path):
    scene, column, rate = line.rstrip("\n").split("\t")
    rates.setdefault(scene, {}).setdefault(column, []).append(rate)
processes = {"cam_press": 2, "nc_slide_loop": 3}
print(f"steps per second, median of {runs} (min-max); 20 000 lock-step steps per run\n")
print("| scene | processes | " + " | ".join(columns) + " |")
print("|---|---|" + "---|" * len(columns))
for scene, by_column in rates.items():
    cells = []
    for c in columns:
        ok = sorted(float(r) for r in by_column.get(c, []) if r != "failed")
        failed = sum(r == "failed" for r in by_column.get(c, []))
        cell = f"{statistics.median(ok):.0f} ({ok[0]:.0f}-{ok[-1]:.0f})" if ok else "-"
        cells.append(cell + (f", {failed} failed" if failed else ""))
    print(f"| {scene} | {processes.get(scene, '?')} nodes + launcher | " + " | ".join(cells) + " |")
PY

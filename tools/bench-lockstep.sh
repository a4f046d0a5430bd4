#!/usr/bin/env bash
# Lock-step cost of a two-process scene next to the physical limit of one DDS exchange per
# step: Cyclone's own ddsperf ping/pong on the same machine, in both of its triggering modes:
# waitset (like the nodes) and listener (ddsperf's default, the faster one here: the sample is
# handled in the receive thread, no wake-up of another thread). Runs all three interleaved,
# RUNS times each, prints the medians (the machines are noisy) and the ratio of mechsim's
# per-step cost to the faster round trip.
#   tools/bench-lockstep.sh [RUNS] [SCENE] [END]
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
scene=${2:-config/scenes/cam_press.yaml}
end=${3:-20 s}
export CYCLONEDDS_URI="file://$PWD/config/dds/cyclonedds-loopback.xml"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"; pkill -f "ddsperf -i 231" 2>/dev/null || true' EXIT

mechsim_rates=()
ddsperf_rates=()
listener_rates=()
for i in $(seq "$runs"); do
  build/bin/mechsim launch "$scene" --end "$end" --no-plot --no-progress --runs-dir "$tmp/runs" \
    --json "$tmp/s.json" >/dev/null 2>&1
  mechsim_rates+=("$(python3 -c "import json;print(json.load(open('$tmp/s.json'))['steps_per_second'])")")
  # ddsperf on domain 231 (outside the launcher's range): pong in the background, ping 4 s,
  # once per triggering mode.
  for mode in waitset listener; do
    ddsperf -i 231 pong "$mode" >/dev/null 2>&1 &
    pong=$!
    sleep 0.3
    ddsperf -i 231 -D 4 ping "$mode" > "$tmp/ping.log" 2>&1 || true
    kill "$pong" 2>/dev/null || true
    wait "$pong" 2>/dev/null || true
    # round trips per second: the median of the per-second counts, first second dropped
    rate="$(grep -o 'cnt [0-9]*' "$tmp/ping.log" | awk '{print $2}' | tail -n +2 | sort -n |
            awk '{a[NR]=$1} END {print (NR ? a[int((NR+1)/2)] : 0)}')"
    if [ "$mode" = waitset ]; then ddsperf_rates+=("$rate"); else listener_rates+=("$rate"); fi
  done
  echo "run $i: mechsim ${mechsim_rates[-1]} steps/s, ddsperf waitset ${ddsperf_rates[-1]}, listener ${listener_rates[-1]} round trips/s"
done
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
m=$(median "${mechsim_rates[@]}")
d=$(median "${ddsperf_rates[@]}")
l=$(median "${listener_rates[@]}")
python3 - "$m" "$d" "$l" <<'PY'
import sys
m, d, l = (float(x) for x in sys.argv[1:4])
fast, name = (l, "listener") if l >= d else (d, "waitset")
print(f"median: mechsim {m:.0f} steps/s ({1e6/m:.1f} us/step); ddsperf round trips/s: waitset {d:.0f} ({1e6/d:.1f} us),"
      f" listener {l:.0f} ({1e6/l:.1f} us)")
print(f"per-step cost / fastest round trip ({name}) = {fast/m:.2f}; against waitset = {d/m:.2f} (target <= 1.5)")
PY

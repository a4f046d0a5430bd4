#!/usr/bin/env bash
# Lock-step throughput under packet loss (docs/faults.md): nc_slide_loop (0.5 s simulated,
# 20 000 steps) with servo, tacho and slide on three hosts of the namespace bed, lossless and
# with LOSS of the packets arriving at every host dropped at random, with and without
# redundant samples, on each vendor layout; runs alternate so that every pair shares the
# same minute. Prints the median steps/s of RUNS runs. Needs root.
#   tools/bench-faults.sh [RUNS=3] [LOSS=0.05]
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-3}"
loss="${2:-0.05}"
export MECHSIM_NETNS_PREFIX=mshfaults
source tools/bench-bed.sh
set_loss() {  # on | off
  for h in 1 2 3; do
    if [ "$1" = on ]; then
      ip netns exec "$MECHSIM_NETNS_PREFIX-h$h" iptables -A INPUT -i eth0 -m statistic --mode random --probability "$loss" -j DROP
    else
      ip netns exec "$MECHSIM_NETNS_PREFIX-h$h" iptables -D INPUT -i eth0 -m statistic --mode random --probability "$loss" -j DROP
    fi
  done
}
one_run() {  # layout redundant(true|false) -> steps/s
  local json="$work/run.json"
  rm -f "$json"
  tools/netns-hosts.sh exec 1 "$mechsim" launch "$scene" --dds "$1" --end '0.5 s' --no-plot --no-progress \
    --runs-dir "$work/runs" --json "$json" --set "faults.redundant_samples=$2" "${three_host_args[@]}" > /dev/null 2>&1 ||
    { echo 0; return; }
  rate "$json"
}
median() { printf "%s\n" "$@" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
printf "%-8s %-10s %12s %12s %7s\n" layout redundant lossless "loss $loss" ratio
for layout in cyclone fastdds mixed; do
  for redundant in false true; do
    clean=(); lossy=()
    for i in $(seq 1 "$runs"); do
      clean+=("$(one_run "$layout" "$redundant")")
      set_loss on
      lossy+=("$(one_run "$layout" "$redundant")")
      set_loss off
    done
    c=$(median "${clean[@]}"); l=$(median "${lossy[@]}")
    printf "%-8s %-10s %12.0f %12.0f %7.2f   (lossless: %s; lossy: %s)\n" "$layout" "$redundant" "$c" "$l" \
      "$(awk -v a="$l" -v b="$c" 'BEGIN {print (b > 0 ? a / b : 0)}')" "${clean[*]%%.*}" "${lossy[*]%%.*}"
  done
done

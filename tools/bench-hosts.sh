#!/usr/bin/env bash
# Lock-step throughput of nc_slide_loop with servo, tacho and slide on three hosts of the
# namespace test bed (tools/netns-hosts.sh) against the same scene on one host's loopback,
# alternating, in the same minute (docs/hosts.md, 'What a network costs'). Needs root.
#   tools/bench-hosts.sh [RUNS=3] [VENDOR=cyclone]
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-3}"
vendor="${2:-cyclone}"
export MECHSIM_NETNS_PREFIX=mshbench
source tools/bench-bed.sh
printf "%-6s %-14s %-14s\n" run "single host" "three hosts"
for i in $(seq 1 "$runs"); do
  "$mechsim" launch "$scene" --dds "$vendor" --no-plot --no-progress --runs-dir "$work/single" --json "$work/s$i.json" > /dev/null 2>&1
  tools/netns-hosts.sh exec 1 "$mechsim" launch "$scene" --dds "$vendor" --no-plot --no-progress --runs-dir "$work/multi" \
    --json "$work/m$i.json" "${three_host_args[@]}" > /dev/null 2>&1
  printf "%-6s %-14.0f %-14.0f\n" "$i" "$(rate "$work/s$i.json")" "$(rate "$work/m$i.json")"
done

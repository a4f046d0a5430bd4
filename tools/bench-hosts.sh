#!/usr/bin/env bash
# Lock-step throughput of nc_slide_loop with servo, tacho and slide on three hosts of the
# namespace test bed (tools/netns-hosts.sh) against the same scene on one host's loopback,
# alternating, in the same minute (docs/hosts.md, 'What a network costs'). Needs root.
#   tools/bench-hosts.sh [RUNS=3] [VENDOR=cyclone]
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-3}"
vendor="${2:-cyclone}"
[ "$(id -u)" -eq 0 ] || { echo "bench-hosts: needs root (network namespaces)" >&2; exit 77; }
mechsim="$PWD/build/bin/mechsim"
scene="$PWD/config/scenes/nc_slide_loop.yaml"
export MECHSIM_NETNS_PREFIX=mshbench
work="$(mktemp -d /tmp/mechsim-bench-hosts.XXXXXX)"
agents=()
cleanup() {
  for pid in "${agents[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  tools/netns-hosts.sh down
  rm -rf "$work"
}
trap cleanup EXIT
tools/netns-hosts.sh up 3
for h in 2 3; do
  tools/netns-hosts.sh exec "$h" "$mechsim" agent --domain 7 --address "10.77.0.$h" --peers 10.77.0.1 \
    --work-dir "$work/agent$h" > "$work/agent$h.log" 2>&1 &
  agents+=($!)
done
rate() { grep -o '"steps_per_second": *[0-9.e+]*' "$1" | head -1 | sed 's/.*: *//'; }
printf "%-6s %-14s %-14s\n" run "single host" "three hosts"
for i in $(seq 1 "$runs"); do
  "$mechsim" launch "$scene" --dds "$vendor" --no-plot --no-progress --runs-dir "$work/single" --json "$work/s$i.json" > /dev/null 2>&1
  tools/netns-hosts.sh exec 1 "$mechsim" launch "$scene" --dds "$vendor" --no-plot --no-progress --runs-dir "$work/multi" \
    --json "$work/m$i.json" --set dds.domain=7 \
    --set hosts.a.address=10.77.0.1 --set hosts.b.address=10.77.0.2 --set hosts.c.address=10.77.0.3 \
    --set participants.servo.host=a --set participants.tacho.host=b --set participants.slide.host=c > /dev/null 2>&1
  printf "%-6s %-14.0f %-14.0f\n" "$i" "$(rate "$work/s$i.json")" "$(rate "$work/m$i.json")"
done

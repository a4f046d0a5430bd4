#!/usr/bin/env bash
# Live-server benchmark (docs/live.md, 'What the run does not notice'): the pace (steps per
# second) of a lock-step run in three forms, one after the other in the same minute, ROUNDS
# times (default 5): without a live server (plain), with `--live` and no client (served),
# with `--live` and one client that subscribes to every channel (watched).
#   tools/bench-live.sh [--rounds N] [--end '60 s'] [--scene cam_press] [--live-rate 60]
#                       [--set KEY=VALUE ...] [--json FILE]
# The client (build/tests/live_watch) subscribes before the nodes start. Prints the steps/s
# of each run and the median ratios watched/served (what a client costs; target >= 0.95)
# and watched/plain (what the live server and its client cost together).
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=5
sets=()
end="60 s"
scene=cam_press
rate=60
json_out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --rounds) rounds="$2"; shift 2 ;;
    --set) sets+=(--set "$2"); shift 2 ;;
    --end) end="$2"; shift 2 ;;
    --scene) scene="$2"; shift 2 ;;
    --live-rate) rate="$2"; shift 2 ;;
    --json) json_out="$2"; shift 2 ;;
    -h|--help) sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "bench-live: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
command -v python3 >/dev/null || { echo "bench-live: needs python3 to read the run summaries" >&2; exit 2; }
[ -x build/bin/mechsim ] && [ -x build/tests/live_watch ] || { echo "bench-live: build first (tools/build.sh, with the tests)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# run TAG [extra launch args...] -> steps/s
run() {
  local tag=$1; shift
  build/bin/mechsim launch "config/scenes/$scene.yaml" --end "$end" --no-progress --no-plot --runs-dir "$tmp/runs" \
    --json "$tmp/$tag.json" ${sets[@]+"${sets[@]}"} "$@" > "$tmp/$tag.log" 2>&1 || { echo "bench-live: run $tag failed: $tmp/$tag.log" >&2; cat "$tmp/$tag.log" >&2; exit 1; }
  python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['steps_per_second'])" "$tmp/$tag.json"
}

printf "%-6s %14s %14s %14s %10s\n" round "plain steps/s" "served" "watched" messages
results=()
for i in $(seq 1 "$rounds"); do
  plain=$(run "plain$i")
  served=$(run "served$i" --live 0 --live-rate "$rate")
  : > "$tmp/watched$i.log"
  build/tests/live_watch "$tmp/watched$i.log" 600 > "$tmp/watch$i.json" &
  watcher=$!
  watched=$(run "watched$i" --live 0 --live-rate "$rate")
  wait "$watcher" || true
  messages=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['messages'])" "$tmp/watch$i.json" 2>/dev/null || echo 0)
  printf "%-6s %14.0f %14.0f %14.0f %10s\n" "$i" "$plain" "$served" "$watched" "$messages"
  results+=("$plain $served $watched $messages")
done
python3 - "$json_out" "$scene" "$end" "$rate" "${sets[*]-}" "${results[@]}" <<'PY'
import json, statistics, sys
out, scene, end, rate, sets = sys.argv[1:6]
rows = [tuple(float(x) for x in r.split()) for r in sys.argv[6:]]
client = statistics.median(w / s for p, s, w, m in rows)
total = statistics.median(w / p for p, s, w, m in rows)
print(f"{scene}, end {end}, live rate {rate} Hz {sets}, {len(rows)} rounds:")
print(f"  median pace watched / served (the client's cost): {client:.3f} (target >= 0.95)")
print(f"  median pace watched / plain (server and client):  {total:.3f}")
if out:
    json.dump({"scene": scene, "end": end, "live_rate_hz": float(rate), "set": sets,
               "median_watched_over_served": client, "median_watched_over_plain": total,
               "rounds": [{"plain_steps_per_s": p, "served_steps_per_s": s, "watched_steps_per_s": w, "messages": int(m)}
                          for p, s, w, m in rows]}, open(out, "w"), indent=2)
PY

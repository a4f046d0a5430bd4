#!/usr/bin/env bash
# Scale benchmark (issue 30, docs/performance.md): lock-step runs of a scene family with K
# = 1, 2, 4, 8, 16 (32) members, for every DDS vendor layout, on one host and spread over
# 2 and 4 hosts of the namespace bed (tools/netns-hosts.sh, needs root). Prints, per point,
# steps/s, participant-steps/s, the CPU time (user and kernel, of the launcher, its nodes
# and, across hosts, the agents' nodes) per participant-step, medians of RUNS interleaved
# runs with min-max, and the ratios to the 8-participant point; writes the table as CSV and
# a PNG of steps/s against K (gnuplot).
#
#   tools/bench-scale.sh [options]
#     --family CMD    scene generator: `CMD K` writes the scene with K members to stdout
#                     (default tools/scale-scene.sh: K independent cam_press pairs)
#     --ks "1 2 4 8 16"   the K values            --runs 3        runs per point
#     --end "4 s"     simulated time per run      --build build   build folder
#     --layouts "cyclone fastdds mixed"           --hosts "1 2 4" host counts (default:
#                     "1 2 4" as root, else "1"; 2 and 4 need root)
#     --out DIR       CSV, PNG and the raw runs (default bench-scale-<date>)
#     --groups G      G process groups (docs/scenes.md), participant i of the scene in group
#                     i mod G, instead of a process per participant (one host only)
#     --processes P   the scene's `processes:` (per_core or a number of groups per vendor;
#                     docs/scenes.md): the launcher packs neighbours into process groups
#     --variant NAME=BUILD[:HOME]   repeatable: compare builds (before/after) in the same
#                     rounds; HOME is the project folder whose config/dds the build uses
#                     (MECHSIM_HOME). Without it: one variant, the --build folder.
#
# CPU is user + system time, less sensitive to the load of a shared machine than wall time;
# every round runs each point once, so the load falls on all points alike. CPU and wall time
# include the start (discovery), as a user's run does.
set -euo pipefail
cd "$(dirname "$0")/.."
family=tools/scale-scene.sh ks="1 2 4 8 16" runs=3 end="4 s" build=build
layouts="cyclone fastdds mixed" hosts="1 2 4" out="bench-scale-$(date +%Y%m%d-%H%M%S)"
variants=() groups=0 hosts_set=0 processes=
[ "$(id -u)" -eq 0 ] || hosts="1"
while [ $# -gt 0 ]; do
  case "$1" in
    --family) family=$2 ;; --ks) ks=$2 ;; --runs) runs=$2 ;; --end) end=$2 ;; --build) build=$2 ;;
    --layouts) layouts=$2 ;; --hosts) hosts=$2 hosts_set=1 ;; --out) out=$2 ;; --variant) variants+=("$2") ;; --groups) groups=$2 ;; --processes) processes=$2 ;;
    -h|--help) sed -n '2,28p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "bench-scale: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift 2
done
[ "$groups" -gt 0 ] && [ "$hosts_set" -eq 0 ] && hosts="1"  # groups run on one host
[ ${#variants[@]} -gt 0 ] || variants=("$(basename "$build")=$build")
for v in "${variants[@]}"; do
  b=${v#*=}; b=${b%%:*}
  [ -x "$b/bin/mechsim" ] || { echo "bench-scale: $b/bin/mechsim is missing (build first, or pass --build)" >&2; exit 1; }
done
# The agents of the namespace bed run the first variant's build.
mechsim=$(b=${variants[0]#*=}; cd "${b%%:*}" && pwd)/bin/mechsim
[ -x /usr/bin/time ] || { echo "bench-scale: /usr/bin/time is missing (Debian package time)" >&2; exit 1; }
mkdir -p "$out/scenes" "$out/runs"
out=$(cd "$out" && pwd)
unset CYCLONEDDS_URI FASTRTPS_DEFAULT_PROFILES_FILE  # the launcher's loopback profiles
for k in $ks; do $family "$k" > "$out/scenes/k$k.yaml"; done

# The namespace bed, only when a multi-host point is asked for: 4 hosts, an agent on 2..4.
max_hosts=1
for h in $hosts; do [ "$h" -gt "$max_hosts" ] && max_hosts=$h; done
agents=()
agent_pids=()
cleanup() {
  for pid in "${agents[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  if [ "$max_hosts" -gt 1 ]; then tools/netns-hosts.sh down; fi
}
trap cleanup EXIT
domain=9
if [ "$max_hosts" -gt 1 ]; then
  [ "$(id -u)" -eq 0 ] || { echo "bench-scale: --hosts above 1 needs root (network namespaces)" >&2; exit 77; }
  export MECHSIM_NETNS_PREFIX=mshscale
  tools/netns-hosts.sh up "$max_hosts"
  for h in $(seq 2 "$max_hosts"); do
    tools/netns-hosts.sh exec "$h" "$mechsim" agent --domain "$domain" --address "10.77.0.$h" --peers 10.77.0.1 --allow-unauthenticated \
      --work-dir "$out/agent$h" > "$out/agent$h.log" 2>&1 &
    agents+=($!)
  done
  sleep 2
  # The agent process itself (inside `ip netns exec`) is the child of the wrapper we started.
  for h in $(seq 2 "$max_hosts"); do
    agent_pids+=("$(pgrep -f -- "--address 10.77.0.$h " | while read -r p; do
      [ "$(cat /proc/$p/comm 2>/dev/null)" = mechsim ] && echo "$p"; done | head -1)")
  done
  echo "bench-scale: agents (pids ${agent_pids[*]}) on hosts 2..$max_hosts, domain $domain" >&2
fi
# CPU seconds (self + reaped children) of the agents: their nodes' CPU in a multi-host run.
agents_cpu() {
  local tck total=0 p
  tck=$(getconf CLK_TCK)
  for p in "${agent_pids[@]}"; do
    [ -n "$p" ] && [ -r "/proc/$p/stat" ] || continue
    total=$(awk -v t="$tck" -v s="$total" '{ sub(/^.*\) /, ""); print s + ($12 + $13 + $14 + $15) / t }' "/proc/$p/stat")
  done
  echo "$total"
}
letters=(a b c d e f g h)
participants_of() {
  awk '/^participants:/{on=1; next} on && /^[^ #]/{on=0} on && /^  [A-Za-z0-9_]+:/{sub(/:.*/, ""); print $1}' "$1"
}
# --set options placing participant i of the scene on host (i mod H).
host_args() {
  local scene=$1 h=$2 i=0 p args=(--set "dds.domain=$domain")
  for j in $(seq 1 "$h"); do args+=(--set "hosts.${letters[$((j - 1))]}.address=10.77.0.$j" --set "hosts.${letters[$((j - 1))]}.control=dds_agent"); done
  for p in $(participants_of "$scene"); do
    args+=(--set "participants.$p.host=${letters[$((i % h))]}")
    i=$((i + 1))
  done
  printf '%s\n' "${args[@]}"
}
# --set options putting participant i of the scene into process group (i mod G).
group_args() {
  local scene=$1 g=$2 i=0 p
  for p in $(participants_of "$scene"); do
    printf '%s\n' --set "participants.$p.process=g$((i % g))"
    i=$((i + 1))
  done
}

echo "variant,hosts,layout,K,round,participants,steps,wall_s,user_s,sys_s,ok" > "$out/runs.csv"
for r in $(seq 1 "$runs"); do
 for v in "${variants[@]}"; do
  name=${v%%=*} vb=${v#*=} vhome=
  case "$vb" in *:*) vhome=${vb#*:} vb=${vb%%:*} ;; esac
  vmechsim="$(cd "$vb" && pwd)/bin/mechsim"
  for h in $hosts; do
    for layout in $layouts; do
      for k in $ks; do
        scene="$out/scenes/k$k.yaml"
        tag="$name-h$h-$layout-k$k-r$r"
        cmd=(env ${vhome:+MECHSIM_HOME=$vhome} "$vmechsim" launch "$scene" --end "$end" --dds "$layout" --no-plot --no-progress --runs-dir "$out/runs"
             --json "$out/$tag.json")
        before=0
        if [ "$groups" -gt 0 ]; then
          [ "$h" -eq 1 ] || { echo "bench-scale: --groups is for one host only (a group member cannot name a host)" >&2; exit 2; }
          mapfile -t extra < <(group_args "$scene" "$groups")
          cmd+=("${extra[@]}")
        fi
        [ -z "$processes" ] || cmd+=(--set "processes=$processes")
        if [ "$h" -gt 1 ]; then
          mapfile -t extra < <(host_args "$scene" "$h")
          cmd=(tools/netns-hosts.sh exec 1 "${cmd[@]}" "${extra[@]}")
          before=$(agents_cpu)
        fi
        ok=1
        /usr/bin/time -f "%U %S" -o "$out/$tag.time" "${cmd[@]}" > "$out/$tag.log" 2>&1 || ok=0
        remote=0
        if [ "$h" -gt 1 ]; then remote=$(awk -v a="$(agents_cpu)" -v b="$before" 'BEGIN { print a - b }'); fi
        read -r user sys < <(tail -1 "$out/$tag.time")
        # Agents' CPU is not split into user and system by /proc's children counters we sum;
        # it is added to user and system in the launcher's proportion.
        python3 - "$out/$tag.json" "$name" "$h" "$layout" "$k" "$r" "$user" "$sys" "$remote" "$ok" >> "$out/runs.csv" <<'PY'
import json, sys
path, variant, h, layout, k, r, user, sys_, remote, ok = sys.argv[1:]
user, sys_, remote = float(user), float(sys_), float(remote)
try:
    s = json.load(open(path))
    n, steps, wall = len(s["nodes"]), s["steps"] if "steps" in s else None, s["wall_time_s"]
    if steps is None:
        steps = min(v["last_step"] for v in s["nodes"].values())
except Exception:
    n, steps, wall, ok = 0, 0, 0, "0"
local = user + sys_
if local > 0:
    user, sys_ = user + remote * user / local, sys_ + remote * sys_ / local
print(f"{variant},{h},{layout},{k},{r},{n},{steps},{wall},{user:.3f},{sys_:.3f},{ok}")
PY
        tail -1 "$out/runs.csv" >&2
      done
    done
  done
 done
done

# Medians with min-max per point; ratios to the point with 8 participants of the same
# hosts and layout (or the nearest below it).
python3 - "$out/runs.csv" "$out/summary.csv" <<'PY'
import csv, statistics, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["ok"] == "1" and int(r["participants"]) > 0]
points = {}
for r in rows:
    points.setdefault((r["variant"], int(r["hosts"]), r["layout"], int(r["K"])), []).append(r)
def fig(rs):
    n = int(rs[0]["participants"])
    rate = [int(r["steps"]) / float(r["wall_s"]) for r in rs]
    cpu = [(float(r["user_s"]) + float(r["sys_s"])) / (n * int(r["steps"])) * 1e6 for r in rs]
    usr = [float(r["user_s"]) / (n * int(r["steps"])) * 1e6 for r in rs]
    sy = [float(r["sys_s"]) / (n * int(r["steps"])) * 1e6 for r in rs]
    return n, rate, cpu, usr, sy
med = statistics.median
out = csv.writer(open(sys.argv[2], "w"))
out.writerow(["variant", "hosts", "layout", "K", "participants", "steps_per_s", "participant_steps_per_s", "cpu_us",
              "cpu_user_us", "cpu_sys_us", "ratio_cpu_to_8", "ratio_psteps_to_8"])
variants = list(dict.fromkeys(r["variant"] for r in rows))
for v, h, layout in sorted({p[:3] for p in points}, key=lambda p: (p[1], p[2], variants.index(p[0]))):
        ks = sorted(p[3] for p in points if p[:3] == (v, h, layout))
        figs = {k: fig(points[(v, h, layout, k)]) for k in ks}
        ref = [k for k in ks if figs[k][0] <= 8]
        ref = max(ref, key=lambda k: figs[k][0]) if ref else None
        print(f"\n{v}: {h} host(s), {layout}" + (f"; ratios to {figs[ref][0]} participants" if ref else ""))
        print(f"{'K':>3} {'part':>4} {'steps/s (min-max)':>22} {'part-steps/s (min-max)':>26} "
              f"{'CPU/part-step us (min-max)':>28} {'user/sys':>11} {'CPU x':>6} {'p-st/s x':>8}")
        for k in ks:
            n, rate, cpu, usr, sy = figs[k]
            ps = [x * n for x in rate]
            rc = rp = float("nan")
            if ref:
                rc = med(cpu) / med(figs[ref][2])
                rp = med(ps) / (med(figs[ref][1]) * figs[ref][0])
            print(f"{k:>3} {n:>4} {med(rate):>8.0f} ({min(rate):>5.0f}-{max(rate):>5.0f}) "
                  f"{med(ps):>10.0f} ({min(ps):>6.0f}-{max(ps):>6.0f}) "
                  f"{med(cpu):>10.1f} ({min(cpu):>5.1f}-{max(cpu):>5.1f}) {med(usr):>5.1f}/{med(sy):<5.1f} "
                  f"{rc:>6.2f} {rp:>8.2f}")
            out.writerow([v, h, layout, k, n, f"{med(rate):.0f}", f"{med(ps):.0f}", f"{med(cpu):.2f}",
                          f"{med(usr):.2f}", f"{med(sy):.2f}", f"{rc:.3f}", f"{rp:.3f}"])
PY

# steps/s against K, one line per hosts x layout.
if command -v gnuplot > /dev/null; then
  plots=()
  for v in "${variants[@]}"; do
   name=${v%%=*}
   for h in $hosts; do
    for layout in $layouts; do
      grep -q "^$name,$h,$layout," "$out/summary.csv" || continue
      grep "^$name,$h,$layout," "$out/summary.csv" | cut -d, -f4,6 | tr , ' ' > "$out/plot-$name-h$h-$layout.dat"
      plots+=("'$out/plot-$name-h$h-$layout.dat' using 1:2 with linespoints title '$name: $layout, $h host(s)'")
    done
   done
  done
  {
    echo "set terminal pngcairo size 900,600"
    echo "set output '$out/steps-per-second.png'"
    echo "set logscale xy 2"
    echo "set xlabel 'K (scene family members)'"
    echo "set ylabel 'steps/s (median)'"
    echo "set grid"
    echo "set title 'Lock-step rate against K: $(basename "$family"), $end simulated'"
    (IFS=,; echo "plot ${plots[*]}")
  } | gnuplot && echo "plot: $out/steps-per-second.png"
fi
echo "table: $out/summary.csv, runs: $out/runs.csv"

#!/usr/bin/env bash
# mechsim against a peer co-simulation master on the same models (issue 42 item 5;
# docs/performance.md "Against a peer: libcosim"). Per scene, ROUNDS interleaved rounds of
#   floor              the models alone: the scene's node steppers called in a loop on one
#                      thread, no transport (`mechsim bench --models-alone`)
#   floor_peer_coupling  the same with every connection coupled as the peer couples it
#                      (Jacobi, held: the .sets file of --peer-system), so that the peer's
#                      rows can be set against the same model work
#   default            `mechsim launch SCENE` as the scene is
#   one_process        the same with every participant in one process (--set processes=1)
#   process_each       the same with a process per participant (--set processes=per_participant)
#   libcosim_0         libcosim 0.11.2, fixedStep, 0 worker threads (all on the calling
#                      thread: its fastest mode here), on the participants exported as FMI 2
#                      co-simulation FMUs (`mechsim bench --peer-system`, the code of
#                      `mechsim fmu export`) with an OspSystemStructure.xml from the scene
#   libcosim_default   the same with libcosim's default worker threads (cores - 1)
# so that the masters of one scene are measured within the same minute. Scenes:
# cam_press, nc_slide_loop, press_line and the 16-station line shaft (`mechsim scene
# stations --stations 16`); a scene the peer cannot take is reported as such, with why.
#
# Each run's steps/s is its own stepping rate (summary.json's steps_per_second, start
# command to the last node done; the floor's and libcosim's loop alone). CPU per step is
# the whole command's (GNU time: user + system CPU of every process of the run, start-up
# included) and, for the floor and libcosim, their loop's alone (getrusage). For mechsim
# the table shows what the whole command holds beside the steps: the CPU of a ten-step run
# of the same layout (`*_start`: start-up, N^2 in the participants, issue 42 item 4) and
# the wall time of the launcher's monolithic reference after the steps. Resident memory is
# the peak of the summed RSS of all its processes (sampled every 0.2 s; at least the
# largest process's peak, for runs shorter than that), so a process per participant pays
# for each process.
#
#   tools/bench-peer.sh [ROUNDS=3] [SCENE_KEY...]   keys: cam_press nc_slide_loop press_line line_shaft_16
#   env: PEER_PREFIX  where tools/build-peer-libcosim.sh installed (default /work/peers, else
#                     $HOME/.cache/mechsim-peers); without bin/cosim_timing there the
#                     libcosim rows are skipped and said so
#        BUILD_DIR    mechsim's build (default build), OUT  the JSON (default $BUILD_DIR/bench-peer.json)
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=${1:-3}
shift || true
keys=("$@")
[ ${#keys[@]} -gt 0 ] || keys=(cam_press nc_slide_loop press_line line_shaft_16)
build=${BUILD_DIR:-build}
mechsim=$build/bin/mechsim
out_json=${OUT:-$build/bench-peer.json}
if [ -n "${PEER_PREFIX:-}" ]; then prefix=$PEER_PREFIX
elif [ -x /work/peers/bin/cosim_timing ]; then prefix=/work/peers
else prefix=$HOME/.cache/mechsim-peers; fi
cosim_timing=$prefix/bin/cosim_timing
export CYCLONEDDS_URI="file://$PWD/config/dds/cyclonedds-loopback.xml"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
trap 'echo "bench-peer: stopped at line $LINENO (exit $?)" >&2' ERR
rows=$tmp/rows.jsonl
: > "$rows"

# Scene file and simulated end of each key: long enough that a run steps for a second or
# more under mechsim's default layout (start-up is in the CPU and memory columns only).
scene_of() {
  case $1 in
    cam_press) echo config/scenes/cam_press.yaml ;;
    nc_slide_loop) echo config/scenes/nc_slide_loop.yaml ;;
    press_line) echo config/scenes/press_line.yaml ;;
    line_shaft_16)
      "$mechsim" scene stations --stations 16 -o "$tmp/line_shaft_16.yaml" >/dev/null
      echo "$tmp/line_shaft_16.yaml" ;;
    *) echo "bench-peer: unknown scene key '$1'" >&2; exit 2 ;;
  esac
}
end_of() {
  case $1 in
    cam_press) echo 20 ;; nc_slide_loop) echo 1 ;; press_line) echo 10 ;; line_shaft_16) echo 2 ;;
  esac
}
# Ten macro steps of the scene: the start-up runs' end, whose CPU is taken off a full run's.
start_end_of() {
  case $1 in
    nc_slide_loop) echo 0.00025 ;; *) echo 0.01 ;;
  esac
}

# Runs a command in its own session under GNU time, sampling the session's summed RSS.
# Appends {"scene", "master", "round", "exit", "wall_s", "cpu_s", "rss_kb", "result"} to the
# rows; `result` is the JSON file the command wrote (read by the summary).
measure() {  # KEY MASTER ROUND RESULT_JSON COMMAND...
  local key=$1 master=$2 round=$3 result=$4
  shift 4
  rm -f "$result"
  # -w: should setsid have to fork (it does when it would lead a process group), it waits.
  setsid -w /usr/bin/time -f '%e %U %S %M' -o "$tmp/time" "$@" > "$tmp/run.log" 2>&1 &
  local pid=$! peak=0 rss status=0
  while kill -0 "$pid" 2>/dev/null; do
    # (no session yet before the child's setsid: ps finds nothing and fails, pipefail)
    rss=$({ ps -s "$pid" -o rss= 2>/dev/null || true; } | awk '{s += $1} END {print s + 0}')
    [ "$rss" -gt "$peak" ] && peak=$rss
    sleep 0.2
  done
  wait "$pid" || status=$?
  local wall=0 user=0 sys=0 maxrss=0
  if [ -s "$tmp/time" ]; then read -r wall user sys maxrss < <(tail -1 "$tmp/time"); elif [ "$status" -eq 0 ]; then status=125; fi
  # A run shorter than the sampling interval: its largest process's peak, from GNU time.
  [ "$maxrss" -le "$peak" ] || peak=$maxrss
  if [ "$status" -ne 0 ]; then cp "$tmp/run.log" "$tmp/fail-$key-$master-$round.log"; fi
  python3 - "$key" "$master" "$round" "$status" "$wall" "$user" "$sys" "$peak" "$result" "$tmp/run.log" >> "$rows" <<'PY'
import json, sys
key, master, rnd, status, wall, user, sys_, peak, result, log = sys.argv[1:]
row = {"scene": key, "master": master, "round": int(rnd), "exit": int(status), "wall_s": float(wall),
       "cpu_s": float(user) + float(sys_), "rss_kb": int(peak)}
try:
    with open(result) as f:
        row["result"] = json.load(f)
except (OSError, ValueError):
    row["result"] = None
    row["log_tail"] = open(log, errors="replace").read()[-400:]
print(json.dumps(row))
PY
}

for key in "${keys[@]}"; do
  scene=$(scene_of "$key")
  end=$(end_of "$key")
  sets=(--set "time.end=$end s")
  start_sets=(--set "time.end=$(start_end_of "$key") s")
  masters=(floor default default_start one_process one_process_start process_each process_each_start)
  # The peer's input: every participant as an FMU and the system structure, once per scene.
  peer_note=""
  if [ ! -x "$cosim_timing" ]; then
    peer_note="libcosim not built ($cosim_timing missing: tools/build-peer-libcosim.sh)"
  elif ! "$mechsim" bench "$scene" "${sets[@]}" --peer-system "$tmp/peer-$key" > "$tmp/peer.log" 2>&1; then
    peer_note=$(tail -1 "$tmp/peer.log")
  else
    masters+=(floor_peer_coupling libcosim_0 libcosim_default)
    peer_sets=()
    while read -r line; do peer_sets+=(--set "$line"); done < "$tmp/peer-$key/peer-coupling.sets"
    sed 's/^/  /' "$tmp/peer.log"
  fi
  [ -z "$peer_note" ] || echo "  $key: libcosim: $peer_note"
  python3 -c 'import json,sys; print(json.dumps({"scene": sys.argv[1], "peer_note": sys.argv[2], "scene_file": sys.argv[3], "end_s": float(sys.argv[4])}))' \
    "$key" "$peer_note" "$scene" "$end" >> "$rows"
  for round in $(seq "$rounds"); do
    for master in "${masters[@]}"; do
      result=$tmp/result.json
      case $master in
        floor) measure "$key" "$master" "$round" "$result" "$mechsim" bench "$scene" "${sets[@]}" --models-alone --json "$result" ;;
        floor_peer_coupling)
          measure "$key" "$master" "$round" "$result" "$mechsim" bench "$scene" "${sets[@]}" "${peer_sets[@]}" --models-alone --json "$result" ;;
        default*|one_process*|process_each*)
          layout=()
          case $master in one_process*) layout=(--set processes=1) ;; process_each*) layout=(--set processes=per_participant) ;; esac
          run_sets=("${sets[@]}")
          case $master in *_start) run_sets=("${start_sets[@]}") ;; esac
          measure "$key" "$master" "$round" "$result" "$mechsim" launch "$scene" "${run_sets[@]}" "${layout[@]}" \
            --no-plot --no-progress --runs-dir "$tmp/runs" --json "$result"
          rm -rf "$tmp/runs" ;;
        libcosim_0) measure "$key" "$master" "$round" "$result" "$cosim_timing" "$tmp/peer-$key/OspSystemStructure.xml" "$end" 0 "$result" ;;
        libcosim_default)
          measure "$key" "$master" "$round" "$result" "$cosim_timing" "$tmp/peer-$key/OspSystemStructure.xml" "$end" \
            "$(( $(nproc) > 1 ? $(nproc) - 1 : 1 ))" "$result" ;;
      esac
      python3 - "$rows" <<'PY'
import json, sys
r = json.loads(open(sys.argv[1]).readlines()[-1])
x = r["result"] or {}
s = x.get("steps_per_second", x.get("steps_per_s"))
print(f"  {r['scene']} round {r['round']} {r['master']}: " + (f"{s:.0f} steps/s" if s and r["exit"] == 0 else f"failed (exit {r['exit']})"))
PY
    done
  done
done

python3 - "$rows" "$out_json" <<'PY'
import json, statistics, sys, os
rows = [json.loads(l) for l in open(sys.argv[1])]
notes = {r["scene"]: r for r in rows if "peer_note" in r}
runs = [r for r in rows if "master" in r]
labels = {"floor": "models alone (floor)", "floor_peer_coupling": "models alone, coupled as libcosim couples", "default": "mechsim, default layout", "one_process": "mechsim, one process",
          "process_each": "mechsim, a process each", "libcosim_0": "libcosim, 0 worker threads",
          "libcosim_default": "libcosim, default worker threads"}
def steps_per_s(r):
    x = r["result"] or {}
    return x.get("steps_per_second", x.get("steps_per_s"))
def steps(r):
    return (r["result"] or {}).get("steps")
def reference_s(r):
    return ((r["result"] or {}).get("reference") or {}).get("wall_time_s", 0.0)
summary = []
print("\n| scene | master | steps/s median (min-max) | x libcosim_0 | x floor | CPU us/step, loop alone | CPU us/step, whole command | start-up CPU s | reference wall s | peak RSS MB (all processes) | runs |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for scene in dict.fromkeys(r["scene"] for r in rows):
    med = {}
    for master in labels:
        mine = [r for r in runs if r["scene"] == scene and r["master"] == master and r["exit"] == 0 and steps_per_s(r)]
        if mine: med[master] = statistics.median(steps_per_s(r) for r in mine)
    for master, label in labels.items():
        all_runs = [r for r in runs if r["scene"] == scene and r["master"] == master]
        ok = [r for r in all_runs if r["exit"] == 0 and steps_per_s(r)]
        if not all_runs:
            if master.startswith("libcosim") and notes.get(scene, {}).get("peer_note"):
                print(f"| {scene} | {label} | not run: {notes[scene]['peer_note']} | | | | | 0 |")
            continue
        if not ok:
            print(f"| {scene} | {label} | failed ({len(all_runs)} runs) | | | | | 0 |")
            continue
        rates = [steps_per_s(r) for r in ok]
        cpu = statistics.median(1e6 * r["cpu_s"] / steps(r) for r in ok)
        starts = [r for r in runs if r["scene"] == scene and r["master"] == master + "_start" and r["exit"] == 0 and r["result"]]
        start_cpu = statistics.median(r["cpu_s"] for r in starts) if starts else None
        if "cpu_s" in (ok[0]["result"] or {}):  # the floor and libcosim: their loop's own
            stepping = statistics.median(1e6 * r["result"]["cpu_s"] / steps(r) for r in ok)
        else:
            # mechsim's whole command holds the start-up and, after the steps, the
            # launcher's monolithic reference over the whole time (summary "reference"),
            # shown beside it: on a loaded machine their wall time is no measure of their
            # CPU, so they are not taken off.
            stepping = None
        reference = statistics.median(reference_s(r) for r in ok) if master in ("default", "one_process", "process_each") else None
        rss = statistics.median(r["rss_kb"] for r in ok) / 1024
        vs_peer = f"{med[master] / med['libcosim_0']:.3f}" if "libcosim_0" in med else "-"
        vs_floor = f"{med['floor'] / med[master]:.2f}" if "floor" in med else "-"
        stepping_text = f"{stepping:.1f}" if stepping is not None else "-"
        start_text = f"{start_cpu:.2f}" if start_cpu is not None else "-"
        reference_text = f"{reference:.2f}" if reference is not None else "-"
        print(f"| {scene} | {label} | {med[master]:.0f} ({min(rates):.0f}-{max(rates):.0f}) | {vs_peer} | {vs_floor} | {stepping_text} | {cpu:.1f} | {start_text} | {reference_text} | {rss:.0f} | {len(ok)} |")
        summary.append({"scene": scene, "master": master, "steps_per_s_median": med[master], "steps_per_s": rates,
                        "cpu_us_per_step_loop": stepping, "cpu_us_per_step_whole_command": cpu, "start_up_cpu_s": start_cpu,
                        "reference_wall_s": reference,
                        "peak_rss_mb_median": rss, "runs": len(ok), "failed": len(all_runs) - len(ok)})
print("\nx libcosim_0: steps/s over libcosim's with 0 worker threads; x floor: the floor's steps/s over this row's (time per step over the floor's);"
      " start-up CPU: a ten-step run of the layout, whole command; reference: the launcher's monolithic run after the steps")
with open(sys.argv[2], "w") as f:
    json.dump({"load_average": os.getloadavg(), "nproc": os.cpu_count(), "scenes": notes, "summary": summary, "runs": runs}, f, indent=1)
print(f"wrote {sys.argv[2]}")
PY

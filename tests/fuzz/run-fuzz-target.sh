#!/usr/bin/env bash
# Runs one libFuzzer target for a bounded time on a fresh copy of its seed corpus (the
# repository's corpus is never written). Exit 0 only when libFuzzer finished the time with
# no crash, leak, timeout, out-of-memory or sanitizer report; a failing input is left as
# <work>/artifacts/crash-*, leak-*, timeout-* or oom-* (reproduce: <target> <that file>).
# Usage: run-fuzz-target.sh TARGET SEED_DIR WORK_DIR SECONDS [DICT [LIBFUZZER_OPTION...]]
set -euo pipefail
target=$1 seeds=$2 work=$3 seconds=$4 dict=${5:-}
shift $(( $# < 5 ? $# : 5 ))  # what is left: extra libFuzzer options (e.g. -max_len=N)
here=$(cd "$(dirname "$0")" && pwd)

rm -rf "$work"
mkdir -p "$work/corpus" "$work/artifacts" "$work/tmp"
cp -r "$seeds"/. "$work/corpus/"

export TMPDIR="$work/tmp"  # the targets' scratch files
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:${UBSAN_OPTIONS:-}"
export LSAN_OPTIONS="suppressions=$here/lsan.supp:print_suppressions=0:${LSAN_OPTIONS:-}"

args=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
      -artifact_prefix="$work/artifacts/")
[ -n "$dict" ] && args+=(-dict="$dict")
args+=("$@")
echo "fuzz: $target ${args[*]} $work/corpus"
status=0
"$target" "${args[@]}" "$work/corpus" >"$work/fuzz.log" 2>&1 || status=$?
# The last status line (cov: ft: corp: exec/s) and the final stats, for the log.
grep -aE '^#[0-9]+ +(DONE|INITED|pulse|NEW|REDUCE)' "$work/fuzz.log" | tail -n 1 || true
grep -aE '^stat::' "$work/fuzz.log" || true
if [ "$status" -ne 0 ]; then
  echo "fuzz: $target failed (exit $status); the report:" >&2
  tail -n 80 "$work/fuzz.log" >&2
  ls -l "$work/artifacts" >&2
  exit 1
fi

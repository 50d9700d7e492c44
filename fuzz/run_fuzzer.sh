#!/usr/bin/env bash
# Runs one libFuzzer harness as a CTest test: first every kept regression input (each once),
# then fuzzing from the seed corpus for CULLCHECK_FUZZ_SECONDS seconds (default 5; e.g. 600 for
# a long run). Fails on any crash, foreign exception, sanitizer report, leak, timeout or
# out-of-memory; the input that caused it is left in WORK/artifacts/ and the line to replay it
# is printed. Fuzzing is seeded (-seed=1) but bounded by time, so the inputs tried differ with
# the machine's speed; a failing input replays exactly.
# Usage: run_fuzzer.sh HARNESS SEED_DIR REGRESSION_DIR WORK_DIR
set -euo pipefail
harness=$1 seeds=$2 regressions=$3 work=$4
seconds=${CULLCHECK_FUZZ_SECONDS:-5}
name=$(basename "$harness")
rm -rf "$work"
mkdir -p "$work/corpus" "$work/artifacts"
[ -d "$seeds" ] || { echo "$name: no seed corpus at $seeds (build the fuzz_seeds target)"; exit 1; }
# Leaks are reported by LeakSanitizer at exit; a report is a failure like any other.
export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
common=(-rss_limit_mb=2048 -timeout=20 -malloc_limit_mb=1024 "-artifact_prefix=$work/artifacts/")

if [ -d "$regressions" ] && [ -n "$(ls -A "$regressions")" ]; then
  "$harness" "${common[@]}" "$regressions"/* >"$work/regressions.log" 2>&1 || {
    cat "$work/regressions.log"
    echo "$name: a kept regression input fails again; replay: $harness $regressions/<input>"
    exit 1
  }
  echo "$name: $(ls "$regressions" | wc -l) regression inputs pass"
fi

status=0
"$harness" "${common[@]}" -seed=1 -max_total_time="$seconds" -print_final_stats=1 "$work/corpus" "$seeds" \
  >"$work/fuzz.log" 2>&1 || status=$?
runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/fuzz.log" | tail -1)
if [ "$status" -ne 0 ]; then
  tail -n 60 "$work/fuzz.log"
  for a in "$work"/artifacts/*; do [ -e "$a" ] && echo "$name: failing input $a; replay: $harness $a"; done
  echo "$name: FAILED after ${runs:-?} executions (exit $status)"
  exit 1
fi
echo "$name: ${runs:-?} executions in ${seconds} s, 0 crashes, corpus $(ls "$work/corpus" | wc -l) new + $(ls "$seeds" | wc -l) seeds"

#!/usr/bin/env bash
# Runs the libFuzzer targets (tests/fuzz) with ASan + UBSan, built with clang into
# build-fuzz. Each target starts from its committed seed corpus and regression inputs and
# grows a working corpus in build-fuzz/corpus/TARGET; a crash, leak, timeout or UB report
# stops with the input saved under build-fuzz/findings/TARGET/ (copy it into
# tests/fuzz/regressions/TARGET/ once fixed, so that every build replays it).
#
# Usage: scripts/fuzz.sh [--ci] [--time SECONDS] [--runs N] [--jobs N] [TARGET...]
#   --ci       60 s per target (the CI mode)
#   --time S   run each target for S seconds (default 60)
#   --runs N   stop each target after N executions instead
#   --jobs N   parallel fuzzing processes per target (default 1)
#   TARGET     blob, mesh (default: both)
set -euo pipefail
shopt -s nullglob
cd "$(dirname "$0")/.."

seconds=60 runs=-1 jobs=1 targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --ci) seconds=60 ;;
    --time) seconds=$2; shift ;;
    --runs) runs=$2; seconds=0; shift ;;
    --jobs) jobs=$2; shift ;;
    blob|mesh) targets+=("$1") ;;
    *) echo "usage: scripts/fuzz.sh [--ci] [--time SECONDS] [--runs N] [--jobs N] [blob|mesh ...]" >&2; exit 2 ;;
  esac
  shift
done
[ ${#targets[@]} -eq 0 ] && targets=(blob mesh)

CC=${CC:-clang} CXX=${CXX:-clang++} cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVOROGEO_FUZZ=ON >/dev/null
cmake --build build-fuzz -j2 --target $(printf 'vorogeo_fuzz_%s ' "${targets[@]}")

declare -A max_len=([blob]=16384 [mesh]=4096)
status=0
for t in "${targets[@]}"; do
  corpus=build-fuzz/corpus/$t findings=build-fuzz/findings/$t log=build-fuzz/fuzz-$t.log
  mkdir -p "$corpus" "$findings"
  echo "fuzz $t: $([ "$runs" -ge 0 ] && echo "$runs runs" || echo "$seconds s") x $jobs job(s)"
  args=(-max_len="${max_len[$t]}" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
        -artifact_prefix="$findings/" "$corpus" "tests/fuzz/corpus/$t" "tests/fuzz/regressions/$t")
  [ "$runs" -ge 0 ] && args=(-runs="$runs" "${args[@]}") || args=(-max_total_time="$seconds" "${args[@]}")
  if [ "$jobs" -gt 1 ]; then
    args=(-jobs="$jobs" -workers="$jobs" "${args[@]}")
  fi
  rm -f fuzz-*.log
  ok=1
  ASAN_OPTIONS=abort_on_error=1:detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "build-fuzz/tests/fuzz/vorogeo_fuzz_$t" "${args[@]}" >"$log" 2>&1 || ok=0
  logs=("$log")
  [ "$jobs" -gt 1 ] && logs=(fuzz-*.log)  # with --jobs, each worker writes fuzz-N.log here
  execs=$(cat "${logs[@]}" | awk '/stat::number_of_executed_units/ {s += $2} END {print s + 0}')
  if [ $ok -eq 1 ]; then
    echo "fuzz $t: clean, $execs executions, corpus $(ls "$corpus" | wc -l) inputs"
  else
    status=1
    echo "fuzz $t: FAILED after $execs executions (log $log, inputs in $findings)" >&2
    cat "${logs[@]}" | grep -E 'ERROR|runtime error|Test unit written|SUMMARY' | head -20 >&2 || true
  fi
  for f in fuzz-*.log; do mv "$f" "build-fuzz/$t-$f"; done
done
exit $status

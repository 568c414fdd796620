#!/usr/bin/env bash
# Sanitizer builds of everything, each running the test suite:
#   asan  AddressSanitizer + UndefinedBehaviorSanitizer (UB aborts), the whole suite;
#   tsan  ThreadSanitizer, the tests that run threads: the bake and partition, the parallel
#         exact batch (their loops on plain threads here, see baker/parallel.h),
#         concurrent runtime queries and the stress test.
# Usage: scripts/check-sanitizers.sh [asan|tsan|all]   (build dirs build-asan, build-tsan)
set -euo pipefail
cd "$(dirname "$0")/.."
which=${1:-all}
jobs=${JOBS:-2}

asan() {
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVOROGEO_SANITIZE=address,undefined >/dev/null
  cmake --build build-asan -j"$jobs"
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-asan --output-on-failure -j"$jobs"
}

tsan() {
  cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVOROGEO_SANITIZE=thread >/dev/null
  cmake --build build-tsan -j"$jobs" --target vorogeo_tests vorogeo
  TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/tests/tsan.supp" \
  VOROGEO_STRESS_SECONDS=${VOROGEO_STRESS_SECONDS:-5} \
    ctest --test-dir build-tsan --output-on-failure -j"$jobs" \
      -R 'stress|determinism|threads|parallel batch|bake|partition' -E 'every shared mesh'
}

case "$which" in
  asan) asan ;;
  tsan) tsan ;;
  all) asan && tsan ;;
  *) echo "usage: scripts/check-sanitizers.sh [asan|tsan|all]" >&2; exit 2 ;;
esac

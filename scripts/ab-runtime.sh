#!/usr/bin/env bash
# Two builds of the runtime library side by side in one process (scripts/ab_runtime.cpp):
# the same random point-to-point queries and one-to-all fields on both, taking turns,
# with the times' ratios and how many answers differ in any bit. For changes smaller
# than the machine's drift between two runs (BENCHMARKS.md's "not kept" figures).
# usage: scripts/ab-runtime.sh BLOB REV_A [REV_B] [--fields N] [--pairs N] [--seed S]
#   REV_A, REV_B: git revisions, each built in a temporary worktree (Release); without
#   REV_B, B is this checkout's working tree (built in a temporary folder too, so that
#   build/ keeps its own configuration).
# A ratio A/B above 1 means B is faster.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
ab_tool=ab-runtime
[ $# -ge 2 ] || { echo "usage: scripts/ab-runtime.sh BLOB REV_A [REV_B] [--fields N] [--pairs N] [--seed S]" >&2; exit 2; }
blob="$1"
shift
[ -f "$blob" ] || { echo "ab-runtime: $blob not found (a blob from vorogeo bake)" >&2; exit 1; }
source "$here/scripts/ab-revisions.sh"
ab_revisions "$@"

# The shared runtime library of revision $2 (or of the working tree when empty) as $out/$1.so.
build_library() {
  ab_build "$1" "$2" vorogeo_runtime_shared
  cp "$(readlink -f "$ab_bin/runtime/libvorogeo.so")" "$out/$1.so"
}

build_library a "$rev_a"
build_library b "$rev_b"
c++ -O2 -std=c++17 -I"$here/runtime/include" -I"$here/tools" "$here/scripts/ab_runtime.cpp" "$here/tools/task_threads.cpp" \
  -o "$out/ab_runtime" -ldl -lpthread
echo "A = ${rev_a}, B = ${rev_b:-working tree}"
"$out/ab_runtime" "$out/a.so" "$out/b.so" "$blob" "${ab_options[@]}"

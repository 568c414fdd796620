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
[ $# -ge 2 ] || { echo "usage: scripts/ab-runtime.sh BLOB REV_A [REV_B] [--fields N] [--pairs N] [--seed S]" >&2; exit 2; }
blob="$1"
rev_a="$2"
shift 2
rev_b=""
if [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; then rev_b="$1"; shift; fi
[ -f "$blob" ] || { echo "ab-runtime: $blob not found (a blob from vorogeo bake)" >&2; exit 1; }
out="$(mktemp -d)"
cleanup() {
  for w in "$out"/tree-*; do [ -d "$w" ] && git -C "$here" worktree remove --force "$w" > /dev/null 2>&1 || true; done
  rm -rf "$out"
}
trap cleanup EXIT

# The shared runtime library of revision $1 (or of the working tree when empty) at $2.
build_library() {
  local rev="$1" dest="$2" src bin
  if [ -z "$rev" ]; then
    src="$here"
    bin="$out/build-working-tree"
  else
    git -C "$here" rev-parse --verify --quiet "$rev^{commit}" > /dev/null || { echo "ab-runtime: no revision $rev" >&2; exit 1; }
    src="$out/tree-$(basename "$dest" .so)"
    git -C "$here" worktree add --detach --quiet "$src" "$rev"
    bin="$src/build"
  fi
  echo "ab-runtime: building the runtime of ${rev:-the working tree}" >&2
  cmake -S "$src" -B "$bin" -DCMAKE_BUILD_TYPE=Release > "$out/cmake.log" 2>&1 ||
    { cat "$out/cmake.log" >&2; echo "ab-runtime: cmake failed for ${rev:-the working tree}" >&2; exit 1; }
  cmake --build "$bin" -j2 --target vorogeo_runtime_shared > "$out/build.log" 2>&1 ||
    { cat "$out/build.log" >&2; echo "ab-runtime: the build failed for ${rev:-the working tree}" >&2; exit 1; }
  cp "$(readlink -f "$bin/runtime/libvorogeo.so")" "$dest"
}

build_library "$rev_a" "$out/a.so"
build_library "$rev_b" "$out/b.so"
c++ -O2 -std=c++17 -I"$here/runtime/include" -I"$here/tools" "$here/scripts/ab_runtime.cpp" "$here/tools/task_threads.cpp" \
  -o "$out/ab_runtime" -ldl -lpthread
echo "A = ${rev_a}, B = ${rev_b:-working tree}"
"$out/ab_runtime" "$out/a.so" "$out/b.so" "$blob" "$@"

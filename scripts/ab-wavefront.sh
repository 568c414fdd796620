#!/usr/bin/env bash
# Two builds of the exact wavefront engine side by side in one process
# (scripts/ab_wavefront.cpp): on the same patches of MESH (default sizes ~200 vertices, as
# the second layer's, and ~3,000, as the first layer's), whole runs from the same sources
# and runs to the same targets, taking turns, with the medians, the ratios of their times
# and how many results differ in any bit. For engine changes smaller than the drift
# between two bakes.
# usage: scripts/ab-wavefront.sh MESH REV_A [REV_B] [--sizes V,V] [--domains N] [--sources N] [--seed S]
#   REV_A, REV_B: git revisions, each built in a temporary worktree (Release); without
#   REV_B, B is this checkout's working tree (built in a temporary folder too).
# A ratio A/B above 1 means B is faster.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
[ $# -ge 2 ] || { echo "usage: scripts/ab-wavefront.sh MESH REV_A [REV_B] [--sizes V,V] [--domains N] [--sources N] [--seed S]" >&2; exit 2; }
mesh="$1"
rev_a="$2"
shift 2
rev_b=""
if [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; then rev_b="$1"; shift; fi
[ -f "$mesh" ] || { echo "ab-wavefront: $mesh not found" >&2; exit 1; }
out="$(mktemp -d)"
cleanup() {
  for w in "$out"/tree-*; do [ -d "$w" ] && git -C "$here" worktree remove --force "$w" > /dev/null 2>&1 || true; done
  rm -rf "$out"
}
trap cleanup EXIT

# Revision $1's baker (the working tree's when empty) with this checkout's shim, as the
# shared library $2; position-independent, its own symbols bound inside it.
build_engine() {
  local rev="$1" dest="$2" src bin
  if [ -z "$rev" ]; then
    src="$here"
    bin="$out/build-working-tree"
  else
    git -C "$here" rev-parse --verify --quiet "$rev^{commit}" > /dev/null || { echo "ab-wavefront: no revision $rev" >&2; exit 1; }
    src="$out/tree-$(basename "$dest" .so)"
    git -C "$here" worktree add --detach --quiet "$src" "$rev"
    bin="$src/build"
  fi
  echo "ab-wavefront: building the engine of ${rev:-the working tree}" >&2
  cmake -S "$src" -B "$bin" -DCMAKE_BUILD_TYPE=Release -DCMAKE_POSITION_INDEPENDENT_CODE=ON > "$out/cmake.log" 2>&1 ||
    { cat "$out/cmake.log" >&2; echo "ab-wavefront: cmake failed for ${rev:-the working tree}" >&2; exit 1; }
  cmake --build "$bin" -j2 --target vorogeo_baker > "$out/build.log" 2>&1 ||
    { cat "$out/build.log" >&2; echo "ab-wavefront: the build failed for ${rev:-the working tree}" >&2; exit 1; }
  c++ -O3 -DNDEBUG -std=c++17 -fPIC -shared -fvisibility=hidden -I"$src/baker" "$here/scripts/ab_wavefront_shim.cpp" \
    "$bin/baker/libvorogeo_baker.a" -ltbb -lpthread -Wl,-Bsymbolic -Wl,--exclude-libs,ALL -o "$dest"
}

build_engine "$rev_a" "$out/a.so"
build_engine "$rev_b" "$out/b.so"
c++ -O2 -std=c++17 "$here/scripts/ab_wavefront.cpp" -o "$out/ab_wavefront" -ldl
echo "A = ${rev_a}, B = ${rev_b:-working tree}"
"$out/ab_wavefront" "$out/a.so" "$out/b.so" "$mesh" "$@"

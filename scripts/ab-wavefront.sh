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
ab_tool=ab-wavefront
[ $# -ge 2 ] || { echo "usage: scripts/ab-wavefront.sh MESH REV_A [REV_B] [--sizes V,V] [--domains N] [--sources N] [--seed S]" >&2; exit 2; }
mesh="$1"
shift
[ -f "$mesh" ] || { echo "ab-wavefront: $mesh not found" >&2; exit 1; }
source "$here/scripts/ab-revisions.sh"
ab_revisions "$@"

# Revision $2's baker (the working tree's when empty), position-independent, with this
# checkout's shim as the shared library $out/$1.so, its own symbols bound inside it.
build_engine() {
  ab_build "$1" "$2" vorogeo_baker -DCMAKE_POSITION_INDEPENDENT_CODE=ON
  c++ -O3 -DNDEBUG -std=c++17 -fPIC -shared -fvisibility=hidden -I"$ab_src/baker" "$here/scripts/ab_wavefront_shim.cpp" \
    "$ab_bin/baker/libvorogeo_baker.a" -ltbb -lpthread -Wl,-Bsymbolic -Wl,--exclude-libs,ALL -o "$out/$1.so"
}

build_engine a "$rev_a"
build_engine b "$rev_b"
c++ -O2 -std=c++17 "$here/scripts/ab_wavefront.cpp" -o "$out/ab_wavefront" -ldl
echo "A = ${rev_a}, B = ${rev_b:-working tree}"
"$out/ab_wavefront" "$out/a.so" "$out/b.so" "$mesh" "${ab_options[@]}"

#!/usr/bin/env bash
# Two builds of the baker's hub-label stage side by side in one process
# (scripts/ab_hub_labels.cpp): computeHubLabels of each on the graph buffer of BLOB, taking
# turns, with the medians, the ratio of their times and whether they made the same tables.
# For label-stage changes smaller than the drift between two bakes.
# usage: scripts/ab-hub-labels.sh BLOB REV_A [REV_B] [--turns N] [--threads N]
#   BLOB: baked with --no-compress (and without --compact), e.g.
#         build/tools/vorogeo bake MESH -o graph.vgeo --no-compress
#   REV_A, REV_B: git revisions, each built in a temporary worktree (Release); without
#   REV_B, B is this checkout's working tree (built in a temporary folder too).
# A ratio A/B above 1 means B is faster.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
ab_tool=ab-hub-labels
[ $# -ge 2 ] || { echo "usage: scripts/ab-hub-labels.sh BLOB REV_A [REV_B] [--turns N] [--threads N]" >&2; exit 2; }
blob="$1"
shift
[ -f "$blob" ] || { echo "ab-hub-labels: $blob not found" >&2; exit 1; }
source "$here/scripts/ab-revisions.sh"
ab_revisions "$@"

# Revision $2's baker (the working tree's when empty), position-independent, with this
# checkout's shim as the shared library $out/$1.so, its own symbols bound inside it.
build_stage() {
  ab_build "$1" "$2" vorogeo_baker -DCMAKE_POSITION_INDEPENDENT_CODE=ON
  c++ -O3 -DNDEBUG -std=c++17 -fPIC -shared -fvisibility=hidden -I"$ab_src/baker" -I"$ab_bin/schema/generated" \
    "$here/scripts/ab_hub_labels_shim.cpp" "$ab_bin/baker/libvorogeo_baker.a" -ltbb -lpthread \
    -Wl,-Bsymbolic -Wl,--exclude-libs,ALL -o "$out/$1.so"
}

build_stage a "$rev_a"
build_stage b "$rev_b"
c++ -O2 -std=c++17 -I"$here/schema" "$here/scripts/ab_hub_labels.cpp" -o "$out/ab_hub_labels" -ldl
echo "A = ${rev_a}, B = ${rev_b:-working tree}"
"$out/ab_hub_labels" "$out/a.so" "$out/b.so" "$blob" "${ab_options[@]}"

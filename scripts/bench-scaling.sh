#!/usr/bin/env bash
# How bake time, peak memory, blob size and query time grow with the mesh (issue #7's
# scale report): spot, igea, and igea after one and two rounds of Loop subdivision
# (x4, x16: made with `vorogeo subdivide`, never stored in the repository). Each mesh is
# baked with defaults and THREADS threads, then `vorogeo bench --runtime-only` times
# PAIRS random point-to-point queries (the workspace's default mode: hub labels where the
# blob has them, else the directed search; and the thesis's bidirectional one, taking turns
# on blocks of 500 pairs, with the ratio of their times) and 5 one-to-all fields (1 thread).
# usage: scripts/bench-scaling.sh [SHARED_DIR] [THREADS] [PAIRS]
# KEEP=DIR keeps the meshes, blobs and reports there (they take ~1.2 GB with x16);
# BAKE_OPTS adds bake options (#7's profile: BAKE_OPTS="--compact --hub-labels
# --inner-rows-at-open"); MESHES picks some of spot igea igea-x4 igea-x16 (default: all).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
shared="${1:-$here/../shared}"
threads="${2:-2}"
pairs="${3:-2000}"
tool="$here/build/tools/vorogeo"
[ -f "$shared/meshes/igea.ply" ] || { echo "bench-scaling: $shared/meshes/igea.ply not found (the shared meshes are needed)"; exit 1; }
shared="$(cd "$shared" && pwd)"  # absolute: the meshes are linked from the output folder
if [ -n "${KEEP:-}" ]; then out="$KEEP"; mkdir -p "$out"; else out="$(mktemp -d)"; trap 'rm -rf "$out"' EXIT; fi
cp_or_subdivide() {  # NAME SOURCE ROUNDS
  [ -f "$out/$1.ply" ] && return
  if [ "$3" = 0 ]; then ln -sf "$2" "$out/$1.ply"; else "$tool" subdivide "$2" -o "$out/$1.ply" --rounds "$3" > /dev/null; fi
}
printf "| mesh | vertices | bake s | peak MB | blob MB | bytes/vertex | 2nd-layer nodes | mode | p2p p50 us (mode / bidirectional) | ratio | p2p p99 us (mode / bidirectional) | ratio | one-to-all ms |\n"
printf "|---|---:|---:|---:|---:|---:|---:|---|---|---:|---|---:|---:|\n"
for name in ${MESHES:-spot igea igea-x4 igea-x16}; do
  case "$name" in
    spot) cp_or_subdivide spot "$shared/meshes/spot.ply" 0 ;;
    igea) cp_or_subdivide igea "$shared/meshes/igea.ply" 0 ;;
    igea-x4) cp_or_subdivide igea-x4 "$shared/meshes/igea.ply" 1 ;;
    igea-x16) cp_or_subdivide igea-x16 "$shared/meshes/igea.ply" 2 ;;
    *) echo "bench-scaling: unknown mesh $name (spot, igea, igea-x4 or igea-x16)"; exit 1 ;;
  esac
  [ -f "$out/$name.vgeo" ] || "$tool" bake "$out/$name.ply" -o "$out/$name.vgeo" --threads "$threads" ${BAKE_OPTS:-} --quiet --report "$out/$name.bake.json"
  "$tool" bench "$out/$name.ply" "$out/$name.vgeo" --runtime-only --pairs "$pairs" --json > "$out/$name.bench.json"
  python3 - "$out/$name.bake.json" "$out/$name.bench.json" "$name" <<'PY'
import json, sys
b = json.load(open(sys.argv[1])); q = json.load(open(sys.argv[2]))
print(f"| {sys.argv[3]} | {b['vertices']} | {b['wall_s']:.1f} | {b['peak_rss_mb']:.0f} | {b['blob_bytes'] / 1e6:.1f} | "
      f"{b['bytes_per_vertex']:.1f} | {b['second_graph']['nodes']} | {q['mode']} | "
      f"{q['sssd_p50_us']:,.0f} / {q['bidirectional_sssd_p50_us']:,.0f} | {q['bidirectional_sssd_p50_us'] / q['sssd_p50_us']:.2f}x | "
      f"{q['sssd_p99_us']:,.0f} / {q['bidirectional_sssd_p99_us']:,.0f} | {q['bidirectional_sssd_p99_us'] / q['sssd_p99_us']:.2f}x | "
      f"{q['msad_p50_ms']:.1f} |")
PY
done

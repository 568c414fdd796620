#!/usr/bin/env bash
# Bakes every mesh of ../shared/meshes with default parameters and prints one table row
# per mesh from the bake reports: wall time, peak memory, blob size, graph sizes.
# usage: scripts/bench-bake.sh [MESH_DIR] [THREADS]   (BAKE_OPTS adds bake options, e.g. --compact)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
meshes="${1:-$here/../shared/meshes}"
threads="${2:-2}"
tool="$here/build/tools/vorogeo"
[ -d "$meshes" ] || { echo "bench-bake: $meshes not found (the shared meshes are needed)"; exit 1; }
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
printf "| mesh | vertices | wall s | partition s | 2nd-layer geodesics s | overlay s | peak MB | blob bytes | bytes/vertex | 1st nodes | 2nd nodes | exact runs |\n"
printf "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n"
for name in spot fandisk rocker-arm stanford-bunny armadillo-50k nefertiti-50k igea; do
  f="$meshes/$name.ply"
  [ -f "$f" ] || continue
  "$tool" bake "$f" -o "$out/$name.vgeo" --threads "$threads" ${BAKE_OPTS:-} --quiet --report "$out/$name.json"
  python3 - "$out/$name.json" "$name" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); s = r["stages_s"]
print(f"| {sys.argv[2]} | {r['vertices']} | {r['wall_s']:.2f} | {s['partition']:.2f} | {s['second-layer geodesics']:.2f} | "
      f"{s.get('first-layer overlay', s.get('first-layer geodesics', 0)):.2f} | {r['peak_rss_mb']:.0f} | {r['blob_bytes']} | "
      f"{r['bytes_per_vertex']:.1f} | {r['first_graph']['nodes']} | {r['second_graph']['nodes']} | {r['exact_runs']} |")
PY
done

#!/usr/bin/env bash
# Geodesic Voronoi partition of every shared mesh (vorogeo voronoi, 32 seeds) and a field
# picture of each (vorogeo render --exact): growing spheres (thesis 3.8) against one
# multi-source labelling query. Blobs and pictures go to DIR (default: a temporary one).
# usage: scripts/bench-voronoi.sh [SHARED_DIR] [DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
shared="${1:-$here/../shared}"
out="${2:-$(mktemp -d)}"
tool="$here/build/tools/vorogeo"
[ -d "$shared/meshes" ] || { echo "bench-voronoi: $shared/meshes not found (the shared meshes are needed)"; exit 1; }
mkdir -p "$out"
printf "| mesh | vertices | growing spheres ms | queries (bounded) | labelling query ms | ratio | labels agree |\n"
printf "|---|---:|---:|---:|---:|---:|---:|\n"
for name in spot fandisk rocker-arm stanford-bunny armadillo-50k nefertiti-50k igea; do
  f="$shared/meshes/$name.ply"
  [ -f "$f" ] || continue
  [ -f "$out/$name.vgeo" ] || "$tool" bake "$f" -o "$out/$name.vgeo" --quiet
  "$tool" render "$f" --blob "$out/$name.vgeo" --source 0 --exact --size 400x400 --out "$out/$name.field.png" >/dev/null
  "$tool" voronoi "$f" "$out/$name.vgeo" --seeds 32 --out "$out/$name.labels.csv" --png "$out/$name.cells.png" \
    > "$out/$name.voronoi.txt"
  python3 - "$out/$name.voronoi.txt" "$name" <<'PY'
import re, sys
t = open(sys.argv[1]).read()
v = re.search(r": (\d+) vertices", t).group(1)
s = re.search(r"growing spheres:\s+([\d.]+) ms, \d+ rounds, (\d+) point-to-point queries \((\d+) bounded\)", t)
m = re.search(r"multi-source labels:\s+([\d.]+) ms \((\d+)x", t)
a = re.search(r"labels agree on ([\d.]+)%", t).group(1)
print(f"| {sys.argv[2]} | {v} | {float(s.group(1)):.0f} | {s.group(2)} ({s.group(3)}) | {m.group(1)} | {m.group(2)}x | {a}% |")
PY
done

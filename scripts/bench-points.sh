#!/usr/bin/env bash
# The surface-point table of BENCHMARKS.md: for every mesh of ../shared/meshes, bake with
# defaults and run `vorogeo eval-points` (10,000 random point pairs against the exact
# engine run from surface points; point vs vertex query time; k nearest).
# usage: scripts/bench-points.sh [SHARED_DIR]   (JSON of every run kept in $KEEP if set)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
shared="${1:-$here/../shared}"
tool="$here/build/tools/vorogeo"
[ -d "$shared/meshes" ] || { echo "bench-points: $shared/meshes not found (the shared meshes are needed)"; exit 1; }
out="${KEEP:-$(mktemp -d)}"
mkdir -p "$out"
[ -n "${KEEP:-}" ] || trap 'rm -rf "$out"' EXIT
printf "| mesh | vertices | point pairs | mean error | p99 error | max error | point p50 us | vertex p50 us | ratio | k-nearest 16/1000 p50 us | 16 point queries p50 us |\n"
printf "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n"
for name in spot fandisk rocker-arm stanford-bunny armadillo-50k nefertiti-50k igea; do
  f="$shared/meshes/$name.ply"
  [ -f "$f" ] || continue
  [ -f "$out/$name.vgeo" ] || "$tool" bake "$f" -o "$out/$name.vgeo" --quiet
  "$tool" eval-points "$f" "$out/$name.vgeo" --pairs 10000 --json > "$out/$name.points.json"
  python3 - "$out/$name.points.json" "$name" <<'PY'
import json, sys
e = json.load(open(sys.argv[1]))
print(f"| {sys.argv[2]} | {e['vertices']} | {e['pairs']} | {100 * e['mean_rel_error']:.3f}% | "
      f"{100 * e['p99_rel_error']:.3f}% | {100 * e['max_rel_error']:.2f}% | {e['point_p50_us']:.0f} | "
      f"{e['vertex_p50_us']:.0f} | {e['point_over_vertex_p50']:.2f} | {e['k_nearest_16_of_1000_p50_us']:.0f} | "
      f"{e['sixteen_point_queries_p50_us']:.0f} |")
PY
done

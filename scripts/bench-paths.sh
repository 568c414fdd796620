#!/usr/bin/env bash
# The geodesic-path table of BENCHMARKS.md: for every mesh of ../shared/meshes, bake with
# defaults and run `vorogeo path --random 2000 --exact` (path length against the distance
# returned with it, against vg_point_distance and against the exact engine, surface
# checks, vg_path time next to vg_point_distance on the same pairs).
# usage: scripts/bench-paths.sh [SHARED_DIR]   (blobs and JSON kept in $KEEP if set)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
shared="${1:-$here/../shared}"
tool="$here/build/tools/vorogeo"
[ -d "$shared/meshes" ] || { echo "bench-paths: $shared/meshes not found (the shared meshes are needed)"; exit 1; }
out="${KEEP:-$(mktemp -d)}"
mkdir -p "$out"
[ -n "${KEEP:-}" ] || trap 'rm -rf "$out"' EXIT
printf "| mesh | vertices | paths | length vs its distance: max | length vs vg_point_distance: mean | p99 | max | over 0.1%% | path over exact: mean | p99 | max | vg_point_distance vs exact: mean | points p50 | path p50 us | path p90 us | distance p50 us | distance p90 us | extraction p50 us | extraction p90 us | ratio |\n"
printf "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n"
for name in spot fandisk rocker-arm stanford-bunny armadillo-50k nefertiti-50k igea; do
  f="$shared/meshes/$name.ply"
  [ -f "$f" ] || continue
  [ -f "$out/$name.vgeo" ] || "$tool" bake "$f" -o "$out/$name.vgeo" --quiet
  "$tool" path "$f" "$out/$name.vgeo" --random 2000 --exact --json > "$out/$name.paths.json"
  python3 - "$out/$name.paths.json" "$name" <<'PY'
import json, sys
e = json.load(open(sys.argv[1]))
print(f"| {sys.argv[2]} | {e['vertices']} | {e['paths']} | {100 * e['max_length_rel_diff']:.5f}% | "
      f"{100 * e['vs_point_distance_mean']:.3f}% | {100 * e['vs_point_distance_p99']:.3f}% | "
      f"{100 * e['vs_point_distance_max']:.2f}% | {e['vs_point_distance_over_0_1pct']} | "
      f"{100 * e['path_vs_exact_mean']:.4f}% | {100 * e['path_vs_exact_p99']:.3f}% | {100 * e['path_vs_exact_max']:.2f}% | "
      f"{100 * e['point_distance_vs_exact_mean']:.4f}% | {e['points_p50']:.0f} | {e['path_p50_us']:.0f} | "
      f"{e['path_p90_us']:.0f} | {e['distance_p50_us']:.0f} | {e['distance_p90_us']:.0f} | "
      f"{e['extraction_p50_us']:.0f} | {e['extraction_p90_us']:.0f} | "
      f"{e['path_over_distance_p50']:.2f} |")
PY
done

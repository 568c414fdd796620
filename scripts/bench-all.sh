#!/usr/bin/env bash
# The summary table of BENCHMARKS.md: for every mesh of ../shared/meshes, bake with
# defaults (2 threads) and measure the runtime against the golden pairs (vorogeo eval)
# and against the exact engine, edge Dijkstra and the thesis's bidirectional search in one
# run (vorogeo bench).
# usage: scripts/bench-all.sh [SHARED_DIR]   (JSON of every run kept in $KEEP if set; BAKE_OPTS adds
# bake options, e.g. --compact)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
shared="${1:-$here/../shared}"
tool="$here/build/tools/vorogeo"
[ -d "$shared/meshes" ] || { echo "bench-all: $shared/meshes not found (the shared meshes are needed)"; exit 1; }
out="${KEEP:-$(mktemp -d)}"
mkdir -p "$out"
[ -n "${KEEP:-}" ] || trap 'rm -rf "$out"' EXIT
printf "| mesh | vertices | bake s | bytes/vertex | p2p p50 us | p2p p99 us | one-to-all ms | mean error | max error | one-to-all mean error (Dijkstra) | p2p vs exact | p2p vs Dijkstra | p2p vs bidirectional | one-to-all vs exact | one-to-all vs Dijkstra |\n"
printf "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n"
for name in spot fandisk rocker-arm stanford-bunny armadillo-50k nefertiti-50k igea; do
  f="$shared/meshes/$name.ply"
  [ -f "$f" ] || continue
  start=$(date +%s.%N)
  "$tool" bake "$f" -o "$out/$name.vgeo" ${BAKE_OPTS:-} --quiet
  end=$(date +%s.%N)
  "$tool" eval "$f" "$out/$name.vgeo" --golden "$shared/golden/$name.pairs.csv" --json > "$out/$name.eval.json"
  "$tool" bench "$f" "$out/$name.vgeo" --json > "$out/$name.bench.json"
  python3 - "$out/$name" "$name" "$start" "$end" <<'PY'
import json, sys
e = json.load(open(sys.argv[1] + ".eval.json"))
b = json.load(open(sys.argv[1] + ".bench.json"))
bake = float(sys.argv[4]) - float(sys.argv[3])
print(f"| {sys.argv[2]} | {e['vertices']} | {bake:.1f} | {e['blob_bytes'] / e['vertices']:.1f} | "
      f"{e['sssd_p50_us']:.0f} | {e['sssd_p99_us']:.0f} | {b['msad_p50_ms']:.1f} | "
      f"{100 * e['mean_rel_error']:.3f}% | {100 * e['max_rel_error']:.2f}% | "
      f"{100 * b['field_mean_rel_error']:.3f}% ({100 * b['dijkstra_mean_rel_error']:.1f}%) | "
      f"{b['speedup_sssd_vs_exact']:.0f}x | {b['speedup_sssd_vs_dijkstra']:.1f}x | "
      f"{b['bidirectional_sssd_p50_us'] / b['sssd_p50_us']:.2f}x | "
      f"{b['speedup_ssad_vs_exact']:.0f}x | {b['speedup_ssad_vs_dijkstra']:.2f}x |")
PY
done

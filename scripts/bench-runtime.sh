#!/usr/bin/env bash
# Bakes every mesh of ../shared/meshes with default parameters and measures the runtime on
# it against the golden pairs: blob size, open time, point-to-point time and error,
# one-to-all time, metric checks. Two table rows per mesh (the table in BENCHMARKS.md): the
# directed point-to-point search, then the thesis's bidirectional one; three with
# BAKE_OPTS=--hub-labels, the hub labels first.
# usage: scripts/bench-runtime.sh [SHARED_DIR]   (BAKE_OPTS adds bake options, e.g. --compact)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
shared="${1:-$here/../shared}"
tool="$here/build/tools/vorogeo"
[ -d "$shared/meshes" ] || { echo "bench-runtime: $shared/meshes not found (the shared meshes are needed)"; exit 1; }
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
printf "| mesh | search | vertices | bytes/vertex | open ms | p2p p50 us | p2p p90 us | p2p p99 us | one-to-all ms | mean error | p99 error | max error | symmetry / triangle violations |\n"
printf "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n"
for name in spot fandisk rocker-arm stanford-bunny armadillo-50k nefertiti-50k igea; do
  f="$shared/meshes/$name.ply"
  [ -f "$f" ] || continue
  "$tool" bake "$f" -o "$out/$name.vgeo" ${BAKE_OPTS:-} --quiet
  modes="directed bidirectional"
  case " ${BAKE_OPTS:-} " in *" --hub-labels "*) modes="labels $modes" ;; esac
  for search in $modes; do
    "$tool" eval "$f" "$out/$name.vgeo" --golden "$shared/golden/$name.pairs.csv" --search "$search" --json > "$out/$name.json"
  python3 - "$out/$name.json" "$name" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
print(f"| {sys.argv[2]} | {r['search']} | {r['vertices']} | {r['blob_bytes'] / r['vertices']:.1f} | {r['open_ms']:.1f} | "
      f"{r['sssd_p50_us']:.0f} | {r['sssd_p90_us']:.0f} | {r['sssd_p99_us']:.0f} | {r['msad_p50_ms']:.1f} | "
      f"{100 * r['mean_rel_error']:.3f}% | {100 * r['p99_rel_error']:.3f}% | {100 * r['max_rel_error']:.2f}% | "
      f"{r['symmetry_violations']} / {r['triangle_violations']} of {r['triples']} |")
PY
  done
done

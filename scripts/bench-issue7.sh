#!/usr/bin/env bash
# Issue #7's igea targets in one run, one table row per bake profile: the accurate graph
# (exact first layer, small second-layer patches, coded distances), the same with hub
# labels, stored or with the inner rows left to vg_open, and the default graph with hub
# labels (coded too). Per profile: bake wall time and peak
# memory (2 threads), bytes per vertex, golden-pair error of the fast mode and of the
# thesis's bidirectional search, and `vorogeo bench --runtime-only` on random pairs (the
# fast mode and the thesis's search taking turns on blocks of 500 pairs) for two seeds,
# with the time vg_open took and the host's own noise at the query's length (the p99 of fixed
# work as long as the p50, which timer interrupts lift on a virtual machine).
# usage: scripts/bench-issue7.sh [SHARED_DIR] [MESH_NAME]   (KEEP=dir keeps the blobs; VOROGEO=path
# runs another build of the tool)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
shared="${1:-$here/../shared}"
name="${2:-igea}"
tool="${VOROGEO:-$here/build/tools/vorogeo}"
mesh="$shared/meshes/$name.ply"
golden="$shared/golden/$name.pairs.csv"
[ -f "$mesh" ] && [ -f "$golden" ] || { echo "bench-issue7: $mesh or $golden not found (the shared meshes and golden pairs are needed)"; exit 1; }
if [ -n "${KEEP:-}" ]; then out="$KEEP"; mkdir -p "$out"; else out="$(mktemp -d)"; trap 'rm -rf "$out"' EXIT; fi

profiles=(
  "accurate|--compact --exact-first-layer --n2 20"
  "accurate+labels|--compact --exact-first-layer --n2 20 --hub-labels"
  "accurate+labels, inner rows at open|--compact --exact-first-layer --n2 20 --hub-labels --inner-rows-at-open"
  "default+labels|--compact --hub-labels"
)
printf "| %s | bake s | peak MB | B/v | fast mode | mean / max error (fast) | mean / max error (thesis) | p2p p50 / p99 us, seed 1 (thesis) | p2p p50 / p99 us, seed 2 (thesis) | thesis / fast p50, p99 | one-to-all ms | open ms | host: fixed work of the p50's length, p99 us |\n" "$name"
printf "|---|---:|---:|---:|---|---|---|---|---|---|---:|---:|---:|\n"
printf "| #7's target | 90 | | 150 | | 0.03%% / 0.5%% | | 20 / 100 | 20 / 100 | | 3 | | |\n"
for entry in "${profiles[@]}"; do
  label="${entry%%|*}"
  opts="${entry#*|}"
  blob="$out/$name-${label//[ ,]/_}.vgeo"
  "$tool" bake "$mesh" -o "$blob" --threads 2 $opts --quiet --report "$out/$label.bake.json"
  fast=directed
  case " $opts " in *" --hub-labels "*) fast=labels ;; esac
  "$tool" eval "$mesh" "$blob" --golden "$golden" --search "$fast" --json > "$out/$label.fast.json"
  "$tool" eval "$mesh" "$blob" --golden "$golden" --search bidirectional --json > "$out/$label.thesis.json"
  for seed in 1 2; do
    "$tool" bench "$mesh" "$blob" --runtime-only --pairs 2000 --sources 5 --seed "$seed" --json > "$out/$label.bench$seed.json"
  done
  python3 - "$out" "$label" "$fast" <<'PY'
import json, sys
out, label, fast = sys.argv[1:]
load = lambda suffix: json.load(open(f"{out}/{label}.{suffix}.json"))
bake, f, t, b1, b2 = load("bake"), load("fast"), load("thesis"), load("bench1"), load("bench2")
err = lambda r: f"{100 * r['mean_rel_error']:.4f}% / {100 * r['max_rel_error']:.3f}%"
p2p = lambda b: (f"{b['sssd_p50_us']:.1f} / {b['sssd_p99_us']:.1f} "
                 f"({b['bidirectional_sssd_p50_us']:.0f} / {b['bidirectional_sssd_p99_us']:.0f})")
ratio = lambda b: (f"{b['bidirectional_sssd_p50_us'] / b['sssd_p50_us']:.1f}x, "
                   f"{b['bidirectional_sssd_p99_us'] / b['sssd_p99_us']:.1f}x")
print(f"| {label} | {bake['wall_s']:.1f} | {bake['peak_rss_mb']:.0f} | {bake['bytes_per_vertex']:.1f} | {fast} | "
      f"{err(f)} | {err(t)} | {p2p(b1)} | {p2p(b2)} | {ratio(b1)}; {ratio(b2)} | "
      f"{min(b1['msad_p50_ms'], b2['msad_p50_ms']):.1f}-{max(b1['msad_p50_ms'], b2['msad_p50_ms']):.1f} "
      f"({min(b1['msad_threads_p50_ms'], b2['msad_threads_p50_ms']):.1f}-{max(b1['msad_threads_p50_ms'], b2['msad_threads_p50_ms']):.1f} "
      f"on {b1['field_threads']} threads) | "
      f"{min(b1['open_ms'], b2['open_ms']):.0f}-{max(b1['open_ms'], b2['open_ms']):.0f} | "
      f"{b1['fixed_work_p99_us']:.0f}, {b2['fixed_work_p99_us']:.0f} |")
PY
done

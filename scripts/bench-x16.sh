#!/usr/bin/env bash
# Issue #7's scale target in one run: igea after two rounds of Loop subdivision (2.15 M
# vertices, made with `vorogeo subdivide`, never stored), baked with hub labels on 2 threads
# under /usr/bin/time (wall time and peak memory), then `vorogeo bench --runtime-only`
# (labels and the thesis's bidirectional search taking turns on blocks of 500 pairs;
# one-to-all on 1 and 2 threads) for two seeds.
# usage: scripts/bench-x16.sh [SHARED_DIR] [N1]
#   N1: first-layer patches (default: the baker's, ~3,000 vertices each); given, the bake
#   also uses zstd level 9 (session 46 measured --n1 1433: BENCHMARKS.md).
# KEEP=DIR keeps the mesh, the blob and its reports (~0.7 GB), and reuses a blob baked
# there before; VOROGEO=path runs another build of the tool.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
shared="${1:-$here/../shared}"
tool="${VOROGEO:-$here/build/tools/vorogeo}"
[ -f "$shared/meshes/igea.ply" ] || { echo "bench-x16: $shared/meshes/igea.ply not found (the shared meshes are needed)"; exit 1; }
[ -x /usr/bin/time ] || { echo "bench-x16: /usr/bin/time not found (it measures the bake's peak memory)"; exit 1; }
if [ -n "${KEEP:-}" ]; then out="$KEEP"; mkdir -p "$out"; else out="$(mktemp -d)"; trap 'rm -rf "$out"' EXIT; fi
mesh="$out/igea-x16.ply"
[ -f "$mesh" ] || "$tool" subdivide "$shared/meshes/igea.ply" -o "$mesh" --rounds 2 > /dev/null
n1="${2:-auto}"
extra=()
[ "$n1" = auto ] || extra=(--n1 "$n1" --level 9)
blob="$out/igea-x16-n1-$n1.vgeo"
if [ ! -f "$blob" ]; then
  # (time's report and the bake's own messages share stderr: shown when the bake fails)
  if ! /usr/bin/time -v "$tool" bake "$mesh" -o "$blob" --threads 2 --compact --hub-labels --inner-rows-at-open \
    "${extra[@]}" --quiet --report "$blob.bake.json" 2> "$blob.bake.time"; then
    cat "$blob.bake.time" >&2
    echo "bench-x16: the bake failed (its messages above)" >&2
    exit 1
  fi
fi
for seed in 1 2; do
  "$tool" bench "$mesh" "$blob" --runtime-only --pairs 2000 --sources 5 --seed "$seed" --json > "$blob.bench$seed.json"
done
python3 - "$blob" "$n1" <<'PY'
import json, os, re, sys
blob_path, n1 = sys.argv[1:]
print("| igea x16 | bake | peak memory | blob | seed | p2p p50 / p99 us (thesis p50, ratio) | one-to-all ms, 1 -> 2 threads | host: fixed work p99 us |")
print("|---|---|---|---|---:|---|---|---:|")
print("| #7's target | 20 min | 16 GB | | | 50 / - | | |")
bake = json.load(open(f"{blob_path}.bake.json")) if os.path.exists(f"{blob_path}.bake.json") else None
peak = ""
if os.path.exists(f"{blob_path}.bake.time"):
    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", open(f"{blob_path}.bake.time").read())
    peak = f"{int(m.group(1)) / 1e6:.2f} GB" if m else ""
wall = f"{bake['wall_s'] / 60:.1f} min" if bake else "(kept blob)"
blob = f"{bake['blob_bytes'] / 1e6:.0f} MB" if bake else ""
for seed in (1, 2):
    b = json.load(open(f"{blob_path}.bench{seed}.json"))
    print(f"| --n1 {n1} | {wall} | {peak} | {blob} | {seed} | "
          f"{b['sssd_p50_us']:.1f} / {b['sssd_p99_us']:.1f} ({b['bidirectional_sssd_p50_us']:.0f} us, "
          f"{b['bidirectional_sssd_p50_us'] / b['sssd_p50_us']:.1f}x) | "
          f"{b['msad_p50_ms']:.1f} -> {b['msad_threads_p50_ms']:.1f} | {b['fixed_work_p99_us']:.0f} |")
PY

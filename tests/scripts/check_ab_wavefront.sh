#!/usr/bin/env bash
# scripts/ab_wavefront.cpp (scripts/ab-wavefront.sh's driver) built and run on two copies of
# one engine build: they must give every result with the same bits, and a mesh that cannot
# be loaded must end the run with a message naming it. The shim is compiled here from the
# baker's engine and mesh-loading sources (the script builds a whole position-independent
# baker per revision instead).
# usage: tests/scripts/check_ab_wavefront.sh SOURCE_DIR MESH [CXX]
set -euo pipefail
src="$1" mesh="$2" cxx="${3:-c++}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
sources=()
for f in mesh mesh_io read_obj read_off read_ply read_stl triangulate mesh_check mesh_repair geodesic_exact geodesic_wavefront; do
  sources+=("$src/baker/$f.cpp")
done
"$cxx" -O1 -std=c++17 -fPIC -shared -fvisibility=hidden -fno-math-errno -ffp-contract=off -I"$src/baker" \
  "$src/scripts/ab_wavefront_shim.cpp" "${sources[@]}" -ltbb -lpthread -Wl,-Bsymbolic -o "$tmp/a.so"
"$cxx" -O2 -std=c++17 "$src/scripts/ab_wavefront.cpp" -o "$tmp/ab_wavefront" -ldl
# (Two files: dlopen gives one handle for one path.)
cp "$tmp/a.so" "$tmp/b.so"
out="$("$tmp/ab_wavefront" "$tmp/a.so" "$tmp/b.so" "$mesh" --sizes 150,600 --domains 2 --sources 3)"
echo "$out"
for size in 150 600; do
  line="$(grep -E "^\| $size \|" <<< "$out")" || { echo "FAIL: no line for patches of $size vertices"; exit 1; }
  grep -qE "\| 12 \|" <<< "$line" || { echo "FAIL: not 12 runs (2 patches x 3 sources x 2 kinds): $line"; exit 1; }
  grep -qE "\| 0 of 4 \|$" <<< "$line" || { echo "FAIL: two copies of one build differ: $line"; exit 1; }
done
if "$tmp/ab_wavefront" "$tmp/a.so" "$tmp/b.so" "$tmp/no-such-mesh.ply" > "$tmp/bad.txt" 2>&1; then
  echo "FAIL: a missing mesh taken"
  exit 1
fi
grep -q "no-such-mesh.ply" "$tmp/bad.txt" || { echo "FAIL: the error does not name the file:"; cat "$tmp/bad.txt"; exit 1; }
echo "ab_wavefront: two copies alike; a missing mesh refused"

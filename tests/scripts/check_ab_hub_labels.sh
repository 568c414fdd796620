#!/usr/bin/env bash
# scripts/ab_hub_labels.cpp (scripts/ab-hub-labels.sh's driver) built and run on two copies
# of one label-stage build: they must make the same tables, and a compressed blob must end
# the run with a message naming the problem. The shim is compiled here from the baker's
# label-stage sources (the script builds a whole position-independent baker per revision
# instead); the blob is baked from MESH with the built tool.
# usage: tests/scripts/check_ab_hub_labels.sh SOURCE_DIR BUILD_DIR TOOL MESH [CXX]
set -euo pipefail
src="$1" bin="$2" tool="$3" mesh="$4" cxx="${5:-c++}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
sources=()
for f in hub_labels hub_label_runs hub_landmarks hub_exit_lists; do sources+=("$src/baker/$f.cpp"); done
"$cxx" -O1 -std=c++17 -fPIC -shared -fvisibility=hidden -I"$src/baker" -I"$src/schema" -I"$bin/schema/generated" \
  "$src/scripts/ab_hub_labels_shim.cpp" "${sources[@]}" -ltbb -lpthread -Wl,-Bsymbolic -Wl,--no-undefined -o "$tmp/a.so"
"$cxx" -O2 -std=c++17 -I"$src/schema" "$src/scripts/ab_hub_labels.cpp" -o "$tmp/ab_hub_labels" -ldl
# (Two files: dlopen gives one handle for one path.)
cp "$tmp/a.so" "$tmp/b.so"
"$tool" bake "$mesh" -o "$tmp/graph.vgeo" --no-compress --quiet
out="$("$tmp/ab_hub_labels" "$tmp/a.so" "$tmp/b.so" "$tmp/graph.vgeo" --turns 2)"
echo "$out"
[ "$(grep -cE '^\| [12] \| [AB] \| [0-9.]+ \| [0-9.]+ \| [0-9.]+ \|$' <<< "$out")" = 2 ] ||
  { echo "FAIL: not one line per turn"; exit 1; }
grep -qE "^medians over 2 turns, 2 threads: .*; tables the same$" <<< "$out" ||
  { echo "FAIL: two copies of one build made different tables"; exit 1; }
"$tool" bake "$mesh" -o "$tmp/packed.vgeo" --quiet
if "$tmp/ab_hub_labels" "$tmp/a.so" "$tmp/b.so" "$tmp/packed.vgeo" > "$tmp/bad.txt" 2>&1; then
  echo "FAIL: a compressed blob taken"
  exit 1
fi
grep -q "packed.vgeo is compressed or coded" "$tmp/bad.txt" ||
  { echo "FAIL: the error does not name the problem:"; cat "$tmp/bad.txt"; exit 1; }
echo "ab_hub_labels: two copies alike; a compressed blob refused"

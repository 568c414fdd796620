#!/usr/bin/env bash
# scripts/ab_runtime.cpp (scripts/ab-runtime.sh's driver) built and run on two copies of
# the built runtime library: two copies of one build must answer every query with the
# same bits, and a file that is no blob must end the run with a message naming it.
# usage: tests/scripts/check_ab_runtime.sh SOURCE_DIR LIBRARY BLOB [CXX]
set -euo pipefail
src="$1" lib="$2" blob="$3" cxx="${4:-c++}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
"$cxx" -O2 -std=c++17 -I"$src/runtime/include" -I"$src/tools" "$src/scripts/ab_runtime.cpp" "$src/tools/task_threads.cpp" \
  -o "$tmp/ab_runtime" -ldl -lpthread
# (Two files: dlopen gives one handle for one path.)
cp "$lib" "$tmp/a.so"
cp "$lib" "$tmp/b.so"
out="$("$tmp/ab_runtime" "$tmp/a.so" "$tmp/b.so" "$blob" --fields 6 --pairs 600)"
echo "$out"
for kind in "point-to-point, 600 pairs" "one-to-all, 1 thread, 6 sources" "one-to-all, 2 threads, 6 sources"; do
  line="$(grep -F "$kind" <<< "$out")" || { echo "FAIL: no line for $kind"; exit 1; }
  grep -q "with other bits 0\b" <<< "$line" || { echo "FAIL: two copies of one build differ: $line"; exit 1; }
done
if "$tmp/ab_runtime" "$tmp/a.so" "$tmp/b.so" "$tmp/a.so" > "$tmp/bad.txt" 2>&1; then
  echo "FAIL: a library file taken for a blob"
  exit 1
fi
grep -q "cannot open $tmp/a.so" "$tmp/bad.txt" || { echo "FAIL: the error does not name the file:"; cat "$tmp/bad.txt"; exit 1; }
echo "ab_runtime: two copies alike; a bad blob refused"

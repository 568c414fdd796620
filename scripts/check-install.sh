#!/usr/bin/env bash
# Installs a build tree into a temporary prefix, then builds and runs every example
# against the installed package (never the build tree) and checks their output: the C
# program (CMake package, and pkg-config), the C++ engine-style and baker-library
# programs, C# through P/Invoke (mono) and Python through ctypes. All four languages
# must print the same distance for the same query. The ctest "install_and_examples".
#   scripts/check-install.sh [BUILD_DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "${1:-$here/build}" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"
fail() { echo "check-install: $*" >&2; exit 1; }
for tool in mcs mono python3 pkg-config cc; do
  command -v "$tool" >/dev/null || fail "$tool not found (scripts/setup.sh installs what is missing)"
done

cmake --install "$build" --prefix "$prefix" >/dev/null
libdir="$(dirname "$(find "$prefix" -name 'libvorogeo.so' | head -n1)")"
[ -f "$libdir/libvorogeo_runtime.a" ] || fail "static runtime not installed"
"$prefix/bin/vorogeo" demo --out "$work/demo" >/dev/null
blob="$work/demo/bumpy-torus.vgeo"

cmake -S "$here/examples" -B "$work/examples" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/examples" -j2 >/dev/null
c_out="$("$work/examples/query_blob" "$blob")"
cpp_out="$("$work/examples/engine_frames" "$blob" 4 10)"
"$work/examples/bake_asset" "$work/demo/bumpy-torus.ply" "$work/library.vgeo" >/dev/null
cmp -s "$work/library.vgeo" "$blob" || fail "the baker library and 'vorogeo bake' gave different bytes"

# pkg-config, shared library.
PKG_CONFIG_PATH="$libdir/pkgconfig" cc -std=c99 -o "$work/query_pc" "$here/examples/c/query_blob.c" \
  $(PKG_CONFIG_PATH="$libdir/pkgconfig" pkg-config --cflags --libs vorogeo) -lm
pc_out="$(LD_LIBRARY_PATH="$libdir" "$work/query_pc" "$blob")"

mcs -nologo -out:"$work/VorogeoExample.exe" "$here/examples/csharp/VorogeoExample.cs"
cs_out="$(LD_LIBRARY_PATH="$libdir" mono "$work/VorogeoExample.exe" "$blob")"
py_out="$(python3 "$here/examples/python/vorogeo_example.py" "$libdir/libvorogeo.so" "$blob")"

line() { grep -m1 '^distance 0 -> ' <<<"$1" || true; }
expected="$(line "$c_out")"
[ -n "$expected" ] || fail "C example printed no distance: $c_out"
for name in cpp pc cs py; do
  var="${name}_out"
  [ "$(line "${!var}")" = "$expected" ] || fail "$name example disagrees: '$(line "${!var}")' vs '$expected'"
done
grep -q "answers identical to one thread: yes" <<<"$cpp_out" || fail "engine example: $cpp_out"
echo "install and examples OK: $expected (C, C via pkg-config, C++, C#, Python); baker library = vorogeo bake"

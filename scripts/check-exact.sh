#!/usr/bin/env bash
# Checks the exact engine against every golden pairs file and field in ../shared/golden.
# Usage: scripts/check-exact.sh [BUILD_DIR]   (takes several minutes for the large meshes)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
shared="$root/../shared"
[ -d "$shared/golden" ] || { echo "check-exact: $shared/golden is absent, nothing to check"; exit 0; }
status=0
for pairs in "$shared"/golden/*.pairs.csv; do
  name="$(basename "$pairs" .pairs.csv)"
  mesh="$shared/meshes/$name.ply"
  "$build/tools/vorogeo" exact "$mesh" --pairs "$pairs" --json || status=1
  for field in "$shared"/golden/"$name".field.*.csv; do
    source="${field##*.field.}"; source="${source%.csv}"
    "$build/tools/vorogeo" exact "$mesh" --source "$source" --field "$field" --json || status=1
  done
done
exit $status

#!/usr/bin/env bash
# Checks both exact engines (wavefront, MMP) against every golden pairs file and field in
# ../shared/golden.
# Usage: scripts/check-exact.sh [BUILD_DIR] [ENGINE...]   (takes several minutes for the large meshes)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
shift || true
engines=("${@:-wavefront}")
[ $# -gt 0 ] || engines=(wavefront mmp)
shared="$root/../shared"
[ -d "$shared/golden" ] || { echo "check-exact: $shared/golden is absent, nothing to check"; exit 0; }
status=0
for engine in "${engines[@]}"; do
  for pairs in "$shared"/golden/*.pairs.csv; do
    name="$(basename "$pairs" .pairs.csv)"
    mesh="$shared/meshes/$name.ply"
    "$build/tools/vorogeo" exact "$mesh" --pairs "$pairs" --json --engine "$engine" || status=1
    for field in "$shared"/golden/"$name".field.*.csv; do
      source="${field##*.field.}"; source="${source%.csv}"
      "$build/tools/vorogeo" exact "$mesh" --source "$source" --field "$field" --json --engine "$engine" || status=1
    done
  done
done
exit $status

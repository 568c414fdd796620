#!/usr/bin/env bash
# Regenerates the README picture from the generated demo mesh (nothing from ../shared):
#   scripts/render-readme-picture.sh [BUILD_DIR]
set -euo pipefail
build=${1:-build}
tool="$build/tools/vorogeo"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$tool" demo --out "$work" >/dev/null
"$tool" render "$work/bumpy-torus.ply" --blob "$work/bumpy-torus.vgeo" --source 0 --exact \
  --view 0,50 --size 420x330 --out docs/bumpy-torus-field.png

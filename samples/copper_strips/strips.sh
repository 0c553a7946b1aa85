#!/usr/bin/env bash
# samples/copper_strips: the three copper strips of Dorsey & Hanrahan 1996 §5.1 (figure 8),
# each script exactly as the paper prints it, over thirty years in six-year steps.
#   samples/copper_strips/strips.sh [BUILD_DIR]     (default: build)
# Writes out/copper_strips/<marine|rural|urban>/tNN/ (a thickness stack per step) and
# out/copper_strips.png: the KM previews in figure 8's layout (rows marine, rural, urban;
# columns 0, 6, ..., 30 years). The rendered contact sheet comes with the layered plugin.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
out="$root/out/copper_strips"
times=(00 06 12 18 24 30)
previews=()
for env in marine rural urban; do
  "$build/bin/patina-texgen" patina "$here/$env.patina" -o "$out/$env" --resolution 256 \
      --times 0,6,12,18,24,30 --seed 1 --quiet
  for t in "${times[@]}"; do previews+=("$out/$env/t$t/preview.png"); done
done
oiiotool "${previews[@]}" --mosaic:pad=8 6x3 -o "$root/out/copper_strips.png"

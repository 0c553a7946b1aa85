#!/usr/bin/env bash
# samples/towers: the two copper-covered towers of Dorsey & Hanrahan 1996 §5.3, one a few
# years old and one decades old.
#   samples/towers/towers.sh [BUILD_DIR]     (default: build)
# Writes out/towers/tower.obj, its maps (accessibility, a year of exposure in Chicago's
# latitude) and out/towers/patina/t04 and t40 (thickness stacks and KM previews).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
out="$root/out/towers"
texgen="$build/bin/patina-texgen"
mkdir -p "$out"

"$texgen" mesh tower --size 4 -o "$out/tower.obj"
"$texgen" mesh plane --size 16 -o "$out/ground.obj"
common=(--mesh "$out/tower.obj" --occluder "$out/ground.obj" -o "$out/maps" --resolution 256 --seed 1)
"$texgen" accessibility "${common[@]}" --max-radius 0.3
"$texgen" exposure "${common[@]}" --latitude 41.98 --longitude -87.9 --timezone -6 \
    --start 2026-01-01 --end 2027-01-01 --sky clear --sun-bins-deg 5 --sky-samples 64

cp "$here/towers.patina" "$out/towers.patina"
"$texgen" patina "$out/towers.patina" --mesh "$out/tower.obj" -o "$out/patina" \
    --resolution 256 --times 4,40 --end-time 40 --seed 1

#!/usr/bin/env bash
# samples/statue: the patina of Dorsey & Hanrahan 1996 §5.2 developing on the project's
# statue over 30 years.
#   samples/statue/statue.sh [BUILD_DIR]     (default: build)
# Bakes the maps statue.patina reads (accessibility; a year of sun and sky exposure in Rome)
# into out/statue/maps/, then runs the script for years 0, 5, ..., 30 into
# out/statue/patina/tNN/ (one thickness stack and a KM preview of the texture per year).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
out="$root/out/statue"
texgen="$build/bin/patina-texgen"
mkdir -p "$out"

"$texgen" mesh statue -o "$out/statue.obj"
"$texgen" mesh plane --size 8 -o "$out/ground.obj"
common=(--mesh "$out/statue.obj" --occluder "$out/ground.obj" -o "$out/maps" --resolution 256 --seed 1)
"$texgen" accessibility "${common[@]}" --max-radius 0.1
"$texgen" exposure "${common[@]}" --latitude 41.9 --longitude 12.5 --timezone 1 \
    --start 2026-01-01 --end 2027-01-01 --sky clear --sun-bins-deg 5 --sky-samples 64

# The script reads maps/... relative to itself: run it from a copy beside the maps.
cp "$here/statue.patina" "$out/statue.patina"
"$texgen" patina "$out/statue.patina" --mesh "$out/statue.obj" -o "$out/patina" \
    --resolution 256 --times 0,5,10,15,20,25,30 --seed 1

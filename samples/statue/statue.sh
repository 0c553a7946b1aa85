#!/usr/bin/env bash
# samples/statue: the patina of Dorsey & Hanrahan 1996 §5.2 developing on the project's
# statue over 30 years (their figures 10 and 11).
#   samples/statue/statue.sh [BUILD_DIR]     (default: build)
# Bakes the maps statue.patina reads (accessibility; a year of sun and sky exposure in Rome)
# into out/statue/maps/, runs the script for each year of $STATUE_TIMES (default
# 0,5,...,30) into out/statue/patina/tNN/ (a thickness stack and a KM preview of the
# texture per year), renders each year with the layered_km shader into
# out/statue/frame_00NN.exr and .png (NN = years), and lays the frames side by side in
# out/statue/frames.png (labelled with the year when oiiotool has a font), and exports the
# series as out/export/statue.glb (glTF, a material variant per year).
# Environment: STATUE_TIMES, STATUE_SPP (default 32), STATUE_WIDTH (default 240).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
out="$root/out/statue"
texgen="$build/bin/patina-texgen"
render="$build/bin/patina-render"
times="${STATUE_TIMES:-0,5,10,15,20,25,30}"
spp="${STATUE_SPP:-32}"
width="${STATUE_WIDTH:-240}"
height=$((width * 3 / 2))
start=$SECONDS
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
    --resolution 256 --times "$times" --seed 1 --quiet
echo "statue: maps and stacks in $((SECONDS - start)) s" >&2
# The series as one glTF asset on the statue's mesh, a material variant per year.
mkdir -p "$root/out/export"
"$texgen" export "$out/patina" -o "$root/out/export/statue.glb" --quiet

# One render per year, framed and lit alike.
font=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
last="${times##*,}"
digits=${#last}
frames=()
IFS=',' read -r -a years <<< "$times"
for y in "${years[@]}"; do
  step=$(printf "t%0${digits}d" "$y")
  f=$(printf %04d "$y")
  sed -e "s|@STACK@|$out/patina/$step/stack.toml|" -e "s|@MESH@|$out/statue.obj|" \
      -e "s|@SKY@|$root/samples/basic/sky.exr|" -e "s|@OUTPUT@|frame_$f.exr|" \
      -e "s|@YEARS@|$y|" -e "s|@WIDTH@|$width|" -e "s|@HEIGHT@|$height|" -e "s|@SPP@|$spp|" \
      "$here/statue_scene.toml.in" > "$out/frame_$f.toml"
  "$render" "$out/frame_$f.toml" --quiet
  frame="$out/frame_$f.png"
  if [[ -f "$font" ]]; then
    oiiotool "$frame" --text:x=9:y=23:size=18:color=0,0,0:font="$font" "$y years" \
        --text:x=8:y=22:size=18:color=1,1,1:font="$font" "$y years" -o "$out/label_$f.png"
    frame="$out/label_$f.png"
  fi
  frames+=("$frame")
done
oiiotool "${frames[@]}" --mosaic:pad=4 "${#frames[@]}x1" -o "$out/frames.tmp.png"
mv "$out/frames.tmp.png" "$out/frames.png"
echo "statue: ${#frames[@]} frames and out/statue/frames.png in $((SECONDS - start)) s" >&2

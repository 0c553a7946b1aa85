#!/usr/bin/env bash
# samples/copper_strips: figure 8 of Dorsey & Hanrahan 1996 (§5.1), the copper strips of
# the marine, rural and urban environments over thirty years in six-year steps, each script
# exactly as the paper prints it.
#   samples/copper_strips/strips.sh [BUILD_DIR]     (default: build)
# Writes
#   out/copper_strips/<marine|rural|urban>/tNN/   a thickness stack per step (patina-texgen)
#   out/copper_strips/render/cell.NNNN.{exr,png}  each strip rendered with the layered_km
#                                                 shader (patina-render)
#   out/copper_strips.png                         the contact sheet: rows marine, rural,
#                                                 urban; columns 0, 6, ..., 30 years
#   out/copper_strips_preview.png                 the same layout from the KM previews
#   out/export/<marine|rural|urban>_strip.glb     each series as glTF 2.0, a variant per age
# Environment: STRIPS_SIZE (pixels per cell, default 192), STRIPS_SPP (default 16).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
out="$root/out/copper_strips"
texgen="$build/bin/patina-texgen"
render="$build/bin/patina-render"
size="${STRIPS_SIZE:-192}"
spp="${STRIPS_SPP:-16}"
envs=(marine rural urban)
times=(00 06 12 18 24 30)
start=$SECONDS

# 1. The stacks: each script over 0-30 years (the script describes year 30).
previews=()
for env in "${envs[@]}"; do
  "$texgen" patina "$here/$env.patina" -o "$out/$env" --resolution 256 \
      --times 0,6,12,18,24,30 --seed 1 --quiet
  for t in "${times[@]}"; do previews+=("$out/$env/t$t/preview.png"); done
done
oiiotool "${previews[@]}" --mosaic:pad=8 6x3 -o "$root/out/copper_strips_preview.png"
echo "copper_strips: stacks in $((SECONDS - start)) s" >&2

# Each strip's series as one glTF asset, a material variant per age (docs/export.md).
mkdir -p "$root/out/export"
for env in "${envs[@]}"; do
  "$texgen" export "$out/$env" -o "$root/out/export/${env}_strip.glb" --quiet
done

# 2. One scene per cell, rendered as frames 1-18 of one patina-render run.
mkdir -p "$out/render"
frame=0
for env in "${envs[@]}"; do
  for t in "${times[@]}"; do
    frame=$((frame + 1))
    f=$(printf %04d "$frame")
    sed -e "s|@STACK@|$out/$env/t$t/stack.toml|" \
        -e "s|@OUTPUT@|cell.$f.exr|" -e "s|@SIZE@|$size|g" -e "s|@SPP@|$spp|" \
        "$here/strip_scene.toml.in" > "$out/render/cell.$f.toml"
  done
done
"$render" "$out/render/cell.####.toml" --frames "1-$frame" --quiet
echo "copper_strips: renders in $((SECONDS - start)) s" >&2

# 3. The contact sheet, labelled when oiiotool has a font to draw with.
font=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
cells=()
frame=0
for env in "${envs[@]}"; do
  for t in "${times[@]}"; do
    frame=$((frame + 1))
    f=$(printf %04d "$frame")
    cell="$out/render/cell.$f.png"
    if [[ -f "$font" ]]; then
      label="$env, $((10#$t)) y"
      oiiotool "$cell" --text:x=7:y=19:size=14:color=0,0,0:font="$font" "$label" \
          --text:x=6:y=18:size=14:color=1,1,1:font="$font" "$label" -o "$out/render/label.$f.png"
      cell="$out/render/label.$f.png"
    fi
    cells+=("$cell")
  done
done
oiiotool "${cells[@]}" --mosaic:pad=4 6x3 -o "$root/out/copper_strips.png.tmp.png"
mv "$root/out/copper_strips.png.tmp.png" "$root/out/copper_strips.png"
echo "copper_strips: out/copper_strips.png in $((SECONDS - start)) s" >&2

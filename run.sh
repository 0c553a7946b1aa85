#!/usr/bin/env bash
# Installs what is missing, builds, renders samples/basic into out/, then bakes the texgen
# maps of the project's statue (samples/bake) and renders them, and runs the three copper
# strip scripts of Dorsey & Hanrahan 1996 §5.1 (samples/copper_strips), the fading samples
# of Kimmel et al. 2013 (samples/fading), the lookdev scene (samples/lookdev) and the weathered stone of Dorsey et al. 1999
# (samples/stone, the slowest; here at 32 samples per pixel, about 10 minutes on 2 cores:
# samples/stone/stone.sh alone renders it at 128, with less noise than weathering).
set -euo pipefail
cd "$(dirname "$0")"
./scripts/build.sh
build="${PATINA_BUILD_DIR:-build}"
mkdir -p out
"$build/bin/patina-render" samples/basic/scene.toml --output out/basic.exr "$@"
echo "wrote out/basic.exr (scene-linear ACEScg, with albedo, normal and depth AOVs) and out/basic.png (sRGB display)"
samples/bake/bake.sh "$build"
echo "wrote out/bake/maps/ (texture stack + stack.toml) and out/bake.png (the maps on four statues)"
samples/statue/statue.sh "$build"
echo "wrote out/statue/ (the §5.2 statue's maps, stacks and a frame per year), out/statue/frames.png and out/export/statue.glb (the series as glTF, a variant per year)"
samples/own_asset/own_asset.sh "$build"
echo "wrote out/own_asset/ (the statue as a Z-up FBX in centimetres, read by its declaration: its maps, patina, statue.glb in +Y-up metres, in_blender.png: Blender's render of it, and units.png: accessibility baked in the right unit and in metres)"
samples/copper_strips/strips.sh "$build"
echo "wrote out/copper_strips/ (patina stacks of the three §5.1 strips, 0-30 years), out/copper_strips.png (rendered with layered_km, laid out as figure 8) and out/export/*_strip.glb (each series as glTF, a variant per age)"
samples/fading/fading.sh "$build"
echo "wrote out/fading/ (fade stacks, reflectance plots like figures 9-13), out/fading/{newspaper,board,cmy}.png and out/export/newspaper.glb (0, 1 and 2 days as glTF variants)"
samples/conservation/conservation.sh "$build"
echo "wrote out/conservation/ (years to a just-noticeable fade of a watercolour chart, newsprint and the Blue Wool references under four lighting policies; a framed print's per-texel forecast; the newspaper restored)"
samples/lookdev/lookdev.sh "$build"
echo "wrote out/lookdev/ (the measured ColorChecker, the lookdev scene under a clear sky, and copper.mp4: the copper ball from 0 to 30 years) and out/viewer/copper/index.html (the series in the browser)"
SPP="${STONE_SPP:-32}" samples/stone/stone.sh "$build"
echo "wrote out/stone/ (weathered sandstone column and marble statue, 0-60 cycles), out/stone/{column,marble}_strip.png and out/export/column.NNNN.vdb (the column's steps as an OpenVDB sequence, frames 1-3)"

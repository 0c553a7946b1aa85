#!/usr/bin/env bash
# samples/own_asset: an artist's asset in another program's conventions, end to end
# (docs/your-asset.md). The project's statue is written by Blender as a Z-up FBX in
# centimetres (to_fbx_zup_cm.py), as 3ds Max or Maya would hand it over. Patina reads its
# axes and unit from the file: uv-check says so; accessibility is baked with a ground plane
# under it (--ground), and once more with the unit wrongly given as metres (a 200 m statue,
# whose every crevice a 10 cm sphere reaches); the statue's patina script grows on it; the
# series is exported as a glTF (+Y up, metres); out/own_asset/units.png shows the two
# accessibility maps side by side on the statue; and unwrap gives the statue a uv set of its
# own, into which accessibility is baked (out/own_asset/unwrapped_accessibility.png).
# Blender opens the exported glb and renders its ages (out/own_asset/in_blender.png).
#   samples/own_asset/own_asset.sh [BUILD_DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
out="$root/out/own_asset"
texgen="$build/bin/patina-texgen"
render="$build/bin/patina-render"
start=$SECONDS
mkdir -p "$out"

"$texgen" mesh statue -o "$out/statue.obj"
blender -b --factory-startup --python-exit-code 1 --python "$here/to_fbx_zup_cm.py" -- \
    "$out/statue.obj" "$out/statue_zup_cm.fbx" > "$out/blender.log" 2>&1
"$texgen" uv-check "$out/statue_zup_cm.fbx" --resolution 256 | head -2

common=(--mesh "$out/statue_zup_cm.fbx" --ground --resolution 256 --seed 1 --quiet)
"$texgen" accessibility "${common[@]}" -o "$out/maps" --max-radius 0.1
"$texgen" exposure "${common[@]}" -o "$out/maps" --latitude 41.9 --longitude 12.5 --timezone 1 \
    --start 2026-01-01 --end 2027-01-01 --sky clear --sun-bins-deg 5 --sky-samples 64
# The same bake with the unit given wrongly: a warning names the file's own unit.
"$texgen" accessibility "${common[@]}" -o "$out/maps_in_metres" --max-radius 0.1 --unit m

cp "$root/samples/statue/statue.patina" "$out/statue.patina"
"$texgen" patina "$out/statue.patina" --mesh "$out/statue_zup_cm.fbx" -o "$out/patina" \
    --resolution 256 --times 0,30 --seed 1 --quiet
"$texgen" export "$out/patina" -o "$out/statue.glb" --quiet
# What the user sees in Blender: its importer, each age variant displayed, Cycles.
blender -b --factory-startup --python-exit-code 1 --python "$here/in_blender.py" -- \
    "$out/statue.glb" "$out/in_blender.png" 320 32 >> "$out/blender.log" 2>&1

# A layout of its own for weathering: Blender's Smart UV Project, headless, as a second uv
# set; the accessibility baked into it, shown as the texture it is.
"$texgen" unwrap "$out/statue_zup_cm.fbx" -o "$out/statue_unwrapped.glb" --quiet
"$texgen" accessibility --mesh "$out/statue_unwrapped.glb" --uv-set 1 --ground --resolution 512 \
    --seed 1 --quiet -o "$out/maps_unwrapped" --max-radius 0.1 --padding 2
oiiotool "$out/maps_unwrapped/accessibility.exr" --ch accessibility --ch 0,0,0 \
    -o "$out/unwrapped_accessibility.png"

sed -e "s|@MESH@|$out/statue_zup_cm.fbx|g" -e "s|@RIGHT@|$out/maps/accessibility.exr|" \
    -e "s|@WRONG@|$out/maps_in_metres/accessibility.exr|" "$here/units.toml.in" > "$out/units.toml"
"$render" "$out/units.toml" --output "$out/units.exr" --quiet
echo "own_asset: out/own_asset/units.png and statue.glb in $((SECONDS - start)) s" >&2

#!/usr/bin/env bash
# samples/bake: bake the texgen maps of the project's statue and render them side by side.
#   samples/bake/bake.sh [BUILD_DIR]     (default: build)
# Writes out/bake/statue.obj, out/bake/ground.obj, out/bake/maps/*.exr + stack.toml (where
# scene.toml looks for them), and renders
# samples/bake/scene.toml to out/bake.exr + out/bake.png (accessibility, ambient occlusion,
# one week of June sun in Rome, and wetness, each shown as the albedo of one statue).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
out="$root/out/bake"
texgen="$build/bin/patina-texgen"
mkdir -p "$out"

"$texgen" mesh statue -o "$out/statue.obj"
"$texgen" mesh plane --size 8 -o "$out/ground.obj"
"$texgen" uv-check "$out/statue.obj" --resolution 512

common=(--mesh "$out/statue.obj" --occluder "$out/ground.obj" -o "$out/maps" --resolution 512 --seed 1)
"$texgen" accessibility "${common[@]}" --max-radius 0.1
"$texgen" ao "${common[@]}" --rays 64
"$texgen" exposure "${common[@]}" --latitude 41.9 --longitude 12.5 --timezone 1 \
    --start 2026-06-15 --end 2026-06-22 --sky clear --sun-bins-deg 1 --sky-samples 64
"$texgen" wetness "${common[@]}" --rain-dir 0.7 -1 0.2 --spread-deg 25 --inclination-power 0.5 \
    --base-height 0.25 --exposure "$out/maps/exposure.exr" --drying 0.5
"$texgen" deposit "${common[@]}" --accessibility "$out/maps/accessibility.exr" \
    --source "sphere center=3,1,0 radius=0.5"

"$build/bin/patina-render" "$here/scene.toml" --output "$root/out/bake.exr"

#!/usr/bin/env bash
# bench/unwrap_vs_bake.sh [BUILD_DIR]: the cost of giving a mesh a layout of its own.
# A uv sphere of 500k triangles (`patina-texgen mesh sphere --resolution 354`) is baked
# with `ao` at SIZE² texels (default 1024, RAYS rays per texel, default 64 as the bakers) on its own uvs;
# then `patina-texgen unwrap` (Blender's Smart UV Project, headless) gives it a second set and
# the same bake runs on that set. Prints the wall times (best of RUNS, default 1) and the
# ratio (unwrap + bake on the new set) / (bake alone): the target is <= 1.5.
#
# Also the cost of reading a mesh's axes and unit: the statue's accessibility bake on
# statue.obj as is, against the same mesh read with --up z --unit cm (a rotation and a scale
# at load) from a copy written z-up in centimetres: the ratio should be 1 within the clock's
# noise.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
size="${SIZE:-1024}"
rays="${RAYS:-64}"
texgen="$build/bin/patina-texgen"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/unwrap_vs_bake.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

# shellcheck source=lib/best_time.sh
source "$here/lib/best_time.sh"

"$texgen" mesh sphere --resolution 354 -o "$tmp/sphere.obj" >/dev/null 2>&1
triangles=$("$texgen" uv-check "$tmp/sphere.obj" --resolution 64 | awk '/^triangles/ {print $2}')
bake=$(best "$texgen" ao --mesh "$tmp/sphere.obj" -o "$tmp/maps" --resolution "$size" \
       --rays "$rays" --seed 1 --quiet)
unwrap=$(best "$texgen" unwrap "$tmp/sphere.obj" -o "$tmp/sphere_unwrapped.glb" --quiet)
rebake=$(best "$texgen" ao --mesh "$tmp/sphere_unwrapped.glb" --uv-set 1 -o "$tmp/maps_unwrapped" \
         --resolution "$size" --rays "$rays" --seed 1 --quiet)
echo "sphere, ${triangles} triangles, ao at ${size}², ${rays} rays: bake ${bake} s; unwrap ${unwrap} s, bake on the new set ${rebake} s"
echo "$unwrap $rebake $bake" | awk '{printf "ratio (unwrap + bake) / bake %.2f  (target <= 1.5)\n", ($1 + $2) / $3}'

# Axes and unit at load: the statue as is, and written z-up in centimetres, read back with
# --up z --unit cm (the same surface in the same place).
"$texgen" mesh statue -o "$tmp/statue.obj" >/dev/null 2>&1
awk '$1 == "v" {printf "v %.6f %.6f %.6f\n", 100 * $2, -100 * $4, 100 * $3; next}
     $1 == "vn" {printf "vn %s %s %s\n", $2, -$4, $3; next} {print}' \
    "$tmp/statue.obj" > "$tmp/statue_zup_cm.obj"
plain=$(best "$texgen" accessibility --mesh "$tmp/statue.obj" -o "$tmp/a" --resolution 512 \
        --max-radius 0.1 --seed 1 --quiet)
converted=$(best "$texgen" accessibility --mesh "$tmp/statue_zup_cm.obj" --up z --unit cm \
            -o "$tmp/b" --resolution 512 --max-radius 0.1 --seed 1 --quiet)
echo "statue accessibility at 512²: as is ${plain} s, z-up centimetres read with --up z --unit cm ${converted} s"
echo "$converted $plain" | awk '{printf "ratio converted / as is %.2f  (target: 1 within noise)\n", $1 / $2}'

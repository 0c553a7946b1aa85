#!/usr/bin/env bash
# samples/stone: weathered stone of Dorsey et al. 1999, rendered with the slab_volume medium
# and its stone_surface boundary (§5), each as a time series laid out in a contact strip.
#   samples/stone/stone.sh [BUILD_DIR]     (default: build; SPP=128 samples per pixel)
#
#  - a sandstone column (samples/stone/column.awk) whose bedding planes erode more on its
#    wet side, rain coming from the front (figure 9): out/stone/column_strip.png, the wet
#    front above the dry back, fresh stone on the left, 180 x 420 pixels a cell;
#  - the project's statue in marble, lit from behind its head so that light shines through
#    the thin parts, yellowing as it weathers (figures 10-11): out/stone/marble_strip.png,
#    336 x 420 pixels a cell.
#  - the column's steps as OpenVDB, out/export/column.NNNN.vdb with column.NNNN.obj (its
#    boundary) beside each.
#
# patina-texgen stone writes one folder per step (volume.exr for the medium, eroded.obj for
# the boundary): 60 wet/dry cycles in 2 steps, 0, 30 and 60 cycles, as far apart as the
# weathering needs to show above the noise. Each step is rendered twice with patina-render,
# SPP/2 samples per pixel under seeds 1 and 2; the picture is their mean (SPP samples), and
# their difference measures its noise. out/stone/measurements.txt compares that noise with
# the change from one step to the next (samples/stone/measure.sh), in the display-referred
# pictures.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
out="$root/out/stone"
texgen="$build/bin/patina-texgen"
render="$build/bin/patina-render"
spp="${SPP:-128}"
half=$(( (spp + 1) / 2 ))
cycles=60
steps=2
mkdir -p "$out"

# Skies (lat-long, +y up, the centre column looking along -z; oiiotool draws them): a soft
# key light high on the right-front for the column; for the marble a dark sky, two dim side
# lights and a small bright light straight behind the statue's head, hidden by it.
oiiotool --pattern fill:top=0.55,0.65,0.85:bottom=0.3,0.27,0.24 512x256 3 \
    --box:color=5,4.6,4:fill=1 380,40,500,110 --blur 61x61 -d half -o "$out/sky_column.exr"
oiiotool --pattern fill:top=0.05,0.055,0.07:bottom=0.02,0.02,0.02 512x256 3 \
    --box:color=9000,8550,7650:fill=1 253,125,259,131 \
    --box:color=0.5,0.5,0.5:fill=1 0,70,40,140 --box:color=0.5,0.5,0.5:fill=1 472,70,512,140 \
    -d half -o "$out/sky_marble.exr"

# scene SUBJECT STEP_DIR SKY CAMERA_FROM CAMERA_TO FOV WIDTH HEIGHT MEDIUM SURFACE SPP
scene() {
    cat <<EOF
[film]
width = $7
height = $8
spp = ${11}
max_depth = 256
seed = 1
[camera]
from = $4
to = $5
fov_deg = $6
[environment]
file = "$3"
colorspace = "lin_rec709"
[[shader]]
name = "stone"
type = "slab_volume"
file = "$2/volume.exr"
$9
[[shader]]
name = "boundary"
type = "stone_surface"
transmission = "diffuse"
${10}
[[object]]
mesh = "$2/eroded.obj"
bsdf = "boundary"
interior = "stone"
EOF
}

# render_series SUBJECT VIEW FROM TO FOV WIDTH HEIGHT SKY MEDIUM SURFACE: per step, two
# renders of SPP/2 samples (seeds 1 and 2) and their mean as <view>.exr and <view>.png (the
# renderer's default display, sRGB through the ACES 1.0 SDR view of ocio/config.ocio).
render_series() {
    local subject="$1" view="$2" start=$SECONDS
    for dir in "$out/$subject"/cycle_*; do
        scene "$subject" "$dir" "$8" "$3" "$4" "$5" "$6" "$7" "$9" "${10}" "$half" > "$dir/$view.toml"
        for seed in 1 2; do
            "$render" "$dir/$view.toml" --seed "$seed" --output "$dir/$view.s$seed.exr" --quiet
        done
        oiiotool "$dir/$view.s1.exr" "$dir/$view.s2.exr" --add --mulc 0.5 -o "$dir/$view.exr"
        oiiotool --colorconfig "$root/ocio/config.ocio" "$dir/$view.exr" --iscolorspace ACEScg \
            --ociodisplay sRGB "ACES 1.0 - SDR Video" -d uint8 -o "$dir/$view.png"
    done
    echo "$subject $view: $(( SECONDS - start )) s for $(ls -d "$out/$subject"/cycle_* | wc -l)" \
        "steps at ${6}x${7}, $spp samples per pixel" >> "$out/timings.txt"
}
: > "$out/timings.txt"

# --- Sandstone column: rain from the front (+z) and above wets the front; deposits make
# black crusts where it stays dry. Slabs on a coarse copy of the column. Beds of 15 cm on a
# 1.7 cm volume grid, so the iron-rich planes (a quarter of each bed) span two voxels and read
# as ochre bands.
awk -f "$here/column.awk" > "$out/column.obj"
awk -f "$here/column.awk" -v segments=16 -v step=0.2 -v flutes=0 -v solid=1 > "$out/column_slabs.obj"
"$texgen" stone --mesh "$out/column.obj" --slab-mesh "$out/column_slabs.obj" --out "$out/column" \
    --stone sandstone --feature-size 0.15 --rain-dir 0 -0.5 -1 --deposit-value 0.3 \
    --cycles "$cycles" --steps "$steps" --tangential-res 6 --depth-res 6 --depth 0.03 \
    --grid 128 --map-resolution 0 --seed 1 --quiet
sandstone='sigma_t = 150.0
stone_albedo = [0.99, 0.96, 0.90]
iron_albedo = [0.90, 0.62, 0.35]
crust_albedo = [0.05, 0.045, 0.04]
forward_k = 0.2
backward_k = -0.2
forward_weight = 0.6
crust_gain = 500.0
iron_gain = 0.35'
render_series column front "[0.0, 1.05, 5.6]" "[0.0, 1.0, 0.0]" 22 180 420 "$out/sky_column.exr" \
    "$sandstone" "eta = 1.55
roughness_exponent = 3.0"
render_series column back "[0.0, 1.05, -5.6]" "[0.0, 1.0, 0.0]" 22 180 420 "$out/sky_column.exr" \
    "$sandstone" "eta = 1.55
roughness_exponent = 3.0"

# The column's steps as an OpenVDB sequence (column.0001.vdb, ...; column.frames.toml says
# which cycle each holds) with its boundary meshes,
# coloured by the medium the renders use.
mkdir -p "$root/out/export"
rm -f "$root/out/export"/column.[0-9][0-9][0-9][0-9].{vdb,obj}  # an earlier run's frames
"$texgen" export "$out/column" -o "$root/out/export/column.vdb" \
    --scene "$out/column/cycle_0000/front.toml" --medium stone --quiet

# --- Marble statue: slabs on a coarse copy of the statue; rain from above.
"$texgen" mesh statue -o "$out/statue.obj"
"$texgen" mesh statue --resolution 24 -o "$out/statue_slabs.obj"
"$texgen" stone --mesh "$out/statue.obj" --slab-mesh "$out/statue_slabs.obj" --out "$out/marble" \
    --stone marble --rain-dir 0.3 -1 -0.2 --deposit-value 0.005 --chemistry-scale 30000 \
    --erosion-events 0.01 \
    --cycles "$cycles" --steps "$steps" --tangential-res 6 --depth-res 6 --depth 0.04 \
    --grid 96 --map-resolution 0 --seed 1 --quiet
render_series marble backlit "[0.0, 1.75, 3.4]" "[0.0, 1.6, 0.0]" 21 336 420 \
    "$out/sky_marble.exr" 'sigma_t = 15.0
stone_albedo = [0.995, 0.993, 0.99]
iron_albedo = [0.95, 0.80, 0.50]
crust_albedo = [0.3, 0.28, 0.25]
forward_k = 0.5
backward_k = -0.2
forward_weight = 0.8
crust_gain = 1.0
iron_gain = 1.0' "eta = 1.5
roughness_exponent = 2.0"

# --- Contact strips: time runs left to right
front=() back=() marble=()
for dir in "$out/column"/cycle_*; do front+=("$dir/front.png"); back+=("$dir/back.png"); done
for dir in "$out/marble"/cycle_*; do marble+=("$dir/backlit.png"); done
n=${#front[@]}
oiiotool "${front[@]}" "${back[@]}" --mosaic:pad=4 "${n}x2" -o "$out/column_strip.png"
oiiotool "${marble[@]}" --mosaic:pad=4 "${#marble[@]}x1" -o "$out/marble_strip.png"
# --- Noise against change, over the stone in each picture (boxes: x0 y0 x1 y1 in pixels)
{
    "$here/measure.sh" column front 60 40 120 380 "$out"/column/cycle_*
    "$here/measure.sh" column back 60 40 120 380 "$out"/column/cycle_*
    "$here/measure.sh" marble backlit 110 90 230 400 "$out"/marble/cycle_*
} | tee "$out/measurements.txt"
cat "$out/timings.txt"
echo "wrote $out/column_strip.png (wet front above dry back, 0-$cycles cycles) and" \
    "$out/marble_strip.png (backlit marble, 0-$cycles cycles)"

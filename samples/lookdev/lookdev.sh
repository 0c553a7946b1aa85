#!/usr/bin/env bash
# samples/lookdev: a lookdev scene (docs/lookdev.md) and a time-lapse movie.
#   samples/lookdev/lookdev.sh [BUILD_DIR]     (default: build)
# Writes into out/lookdev/:
#   sky.exr           the clear sky of `patina-texgen sky` (sun 35 degrees up, SSE)
#   chart.exr/.png    the measured ColorChecker under D65 (colorchecker.toml, Un-tone-mapped)
#   lookdev.exr/.png  the chart, an 18 % grey ball, a chrome ball and two shader balls (urban
#                     copper after 12 years; congo red faded a day under F11) under the sky,
#                     through the view VIEW (default "ACES 1.0 - SDR Video"; "Un-tone-mapped"
#                     and "Raw" are the config's others)
#   copper.mp4        the shader ball's copper from 0 to 30 years, a frame per step, through
#                     the same view (ffmpeg, H.264)
# and out/viewer/copper/index.html: the copper series in the browser viewer
# (patina-texgen view; open it from the folder).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
out="$root/out/lookdev"
texgen="$build/bin/patina-texgen"
render="$build/bin/patina-render"
view="${VIEW:-ACES 1.0 - SDR Video}"
spp="${LOOKDEV_SPP:-64}"
mkdir -p "$out"
start=$SECONDS

"$render" "$here/colorchecker.toml" --output "$out/chart.exr" --quiet

# The sky, and the [sun] the command prints for it.
sky_toml=$("$texgen" sky -o "$out/sky.exr" --sun-elevation 35 --sun-azimuth 150 |
          sed "s|^file = .*|file = \"$out/sky.exr\"|")
# The materials: the urban copper strip of D&H 1996 §5.1 over 30 years, and a dye faded a
# day under the fluorescent lamp (samples/fading: F11 at 100 W/m^2).
"$texgen" patina "$root/samples/copper_strips/urban.patina" -o "$out/copper" --resolution 256 \
    --times 0,6,12,18,24,30 --seed 1 --quiet
"$texgen" fade --dose 8.64e6 --duration 1d --illuminant F11 --material congo_red \
    --entries 64 --out "$out/congo_red" --quiet

# scene STACK OUTPUT WIDTH HEIGHT [DISPLAY]: the lookdev scene with the copper of STACK.
# Light scattered twice or more is clamped at 4 (about ten times the floor's radiance): the
# polished balls' caustics on the floor are fireflies at these samples (docs/scene-format.md).
scene() {
  local stack=$1 output=$2 width=$3 height=$4 display=${5:-sRGB}
  cat <<EOF
# Written by samples/lookdev/lookdev.sh: the lookdev scene (docs/lookdev.md).
[film]
width = $width
height = $height
spp = $spp
seed = 1
max_depth = 6
clamp_indirect = 4

[camera]
from = [0.0, 0.55, 2.6]
to = [0.0, 0.32, 0.0]
fov_deg = 30

[output]
file = "$output"
display = "$display"
view = "$view"

$sky_toml

[[shader]]
name = "floor"
type = "lambert"
reflectance = 0.3

[[shader]]
name = "grey18"
type = "lambert"
reflectance = 0.18

# Chrome: Cr's n + ik near 550 nm (about 3.2 + 3.3i), a perfect mirror.
[[shader]]
name = "chrome"
type = "conductor"
eta = 3.2
k = 3.3
roughness = 0.0

[[shader]]
name = "copper"
type = "layered_km"
stack = "$stack"

[[shader]]
name = "congo_red"
type = "spectral_km"
fade = "$out/congo_red/fade.toml"
coat = 0.5

[[object]]
shape = "plane"
size = 20
bsdf = "floor"

[[object]]
shape = "sphere"
center = [-0.75, 0.2, 0.3]
radius = 0.2
bsdf = "grey18"

[[object]]
shape = "sphere"
center = [-0.3, 0.2, 0.5]
radius = 0.2
bsdf = "chrome"

[[object]]
shape = "sphere"
center = [0.3, 0.25, 0.4]
radius = 0.25
bsdf = "copper"

[[object]]
shape = "sphere"
center = [0.8, 0.2, 0.3]
radius = 0.2
bsdf = "congo_red"
EOF
  # The chart: 6 x 4 patches of 0.09 m on a stand behind the balls, facing the camera.
  local i=0 name
  while IFS= read -r name; do
    local col=$((i % 6)) row=$((i / 6))
    cat <<EOF

[[shader]]
name = "patch$i"
type = "lambert"
reflectance_spectrum = { file = "$root/data/colorchecker_ohta1997.csv", column = "$name" }

[[object]]
shape = "plane"
size = 0.09
bsdf = "patch$i"
transform = { rotate_deg = [90, 0, 0], translate = [$(awk "BEGIN { print -0.25 + 0.1 * $col }"), $(awk "BEGIN { print 0.95 - 0.1 * $row }"), -0.3] }
EOF
    i=$((i + 1))
  done < <(grep -v '^#' "$root/data/colorchecker_ohta1997.csv" | head -1 | tr ',' '\n' | tail -n +2)
}

scene "$out/copper/t12/stack.toml" lookdev.exr 640 360 > "$out/lookdev.toml"
"$render" "$out/lookdev.toml" --quiet
echo "lookdev: chart and scene in $((SECONDS - start)) s" >&2

# The time-lapse: a frame per step of the copper series, through the same view, into H.264.
mkdir -p "$out/frames"
frame=0
for t in 00 06 12 18 24 30; do
  frame=$((frame + 1))
  f=$(printf %04d "$frame")
  scene "$out/copper/t$t/stack.toml" "frame.$f.exr" 320 180 "Rec.1886 Rec.709" \
    > "$out/frames/frame.$f.toml"
done
"$render" "$out/frames/frame.####.toml" --frames "1-$frame" --quiet
# Frames for a video display, into a movie tagged BT.709.
"$root/scripts/make_movie.sh" "$out/frames/frame.%04d.png" 2 "$out/copper.mp4" "$frame"

# The series in the browser: exported as glTF variants, then the viewer's folder.
mkdir -p "$root/out/viewer"
"$texgen" export "$out/copper" -o "$out/copper.glb" --quiet
"$texgen" view "$out/copper.glb" -o "$root/out/viewer/copper" --title "urban copper, 0-30 years" -q
echo "lookdev: $frame-frame time-lapse in $((SECONDS - start)) s" >&2

#!/usr/bin/env bash
# samples/conservation: how long can it be shown, and what did it look like before
# (docs/forecast.md).
#   samples/conservation/conservation.sh [BUILD_DIR]     (default: build)
# Writes into out/conservation/:
#   chart/<mixture>/    a watercolour-like C/M/Y chart (the Table V pigments at the rates of
#                       real lightfastness, rate set `watercolour`) under the four policies of
#                       policies.toml: forecast.png, forecast.csv, policies.csv
#   newspaper/          newsprint (a free sheet; its lignin yellowing, rate set lignin_only)
#                       under the same policies
#   blue_wool/          ISO Blue Wool 1-8 under the same policies, at dE2000 1.6
#   years.csv           years to a just-noticeable fade (dE2000 1), every material x policy
#   print/              a framed print on the wall facing a south window: the exposure map
#                       of a (weekly-sampled) Chicago year, fade_forecast.exr (years to
#                       dE2000 1 and dE2000 after 5 years per texel), its pictures and
#                       print_forecast.glb (both maps as glTF variants; in the browser:
#                       out/viewer/print_forecast/index.html)
#   restored/           the newspaper of samples/fading yellowed by two June days, restored
#                       from its faded texture: restored.png, confidence.png, and
#                       side_by_side.png (faded | restored | confidence)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
out="$root/out/conservation"
texgen="$build/bin/patina-texgen"
rm -rf "$out"
mkdir -p "$out"
policies="$here/policies.toml"
# box FILE x0 x1 y0 y1 z0 z1: an axis-aligned box as an OBJ
source "$root/samples/lib/obj.sh"

# ---- The chart, the newspaper, the Blue Wool references under four policies ---------------
mixtures=(cyan magenta yellow cyan_magenta cyan_yellow magenta_yellow cyan_magenta_yellow)
for m in "${mixtures[@]}"; do
    mkdir -p "$out/chart/$m"
    "$texgen" forecast --material "$m" --rates watercolour --policies "$policies" --years 100 \
        --log-years \
        -o "$out/chart/$m" > "$out/chart/$m/table.txt"
done
mkdir -p "$out/newspaper"
"$texgen" forecast --material newsprint_free --rates lignin_only --policies "$policies" --years 100 \
    --log-years \
    -o "$out/newspaper" > "$out/newspaper/table.txt"
for k in 1 2 3 4 5 6 7 8; do
    mkdir -p "$out/blue_wool/$k"
    "$texgen" forecast --blue-wool "$k" --policies "$policies" --threshold 1.6 --years 100 \
        -o "$out/blue_wool/$k" > "$out/blue_wool/$k/table.txt"
done

# years.csv: material, policy, years (policies.csv: the policy is the first field, quoted,
# the years the tenth; the policies' names hold no comma)
{
    echo "material,policy,years_to_dE2000_1"
    for d in "$out"/chart/* "$out/newspaper"; do
        name="$(basename "$d")"
        [ "$name" = newspaper ] && name=newsprint_free
        grep -v '^#' "$d/policies.csv" | tail -n +2 |
            awk -F, -v m="$name" '{ gsub(/"/, "", $1); printf "%s,%s,%s\n", m, $1, $10 }'
    done
} > "$out/years.csv"

# ---- A framed print facing a south window: where it fades first ---------------------------
# A room 4 m wide, 2.5 m deep and 2.6 m high (north -z) with a tall window (1.6 m x 2.2 m)
# in its south wall; the print, 60 x 50 cm, hangs on the north wall facing it, in a frame
# 4 cm deep. The winter sun, low in the south, reaches it through the window.
pr="$out/print"
mkdir -p "$pr"
cat > "$pr/print.obj" <<OBJ
v -0.3 1.2 -2.0
v 0.3 1.2 -2.0
v 0.3 1.7 -2.0
v -0.3 1.7 -2.0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
f 1/1/1 2/2/1 3/3/1
f 1/1/1 3/3/1 4/4/1
OBJ
occluders=()
add() { box "$pr/$1.obj" "${@:2}"; occluders+=(--occluder "$pr/$1.obj"); }
add frame_left   -0.35 -0.30 1.15 1.75 -2.0 -1.96
add frame_right   0.30  0.35 1.15 1.75 -2.0 -1.96
add frame_bottom -0.30  0.30 1.15 1.20 -2.0 -1.96
add frame_top    -0.30  0.30 1.70 1.75 -2.0 -1.96
add wall_north   -2.1 2.1 -0.1 2.7 -2.15 -2.05
add wall_east     2.0 2.1 -0.1 2.7 -2.15 0.6
add wall_west    -2.1 -2.0 -0.1 2.7 -2.15 0.6
add floor        -2.1 2.1 -0.1 0.0 -2.15 0.6
add ceiling      -2.1 2.1 2.6 2.7 -2.15 0.6
add south_left   -2.1 -0.8 -0.1 2.7 0.5 0.6
add south_right   0.8 2.1 -0.1 2.7 0.5 0.6
add below_window -0.8 0.8 -0.1 0.3 0.5 0.6
add above_window -0.8 0.8 2.5 2.7 0.5 0.6
"$texgen" exposure --mesh "$pr/print.obj" "${occluders[@]}" -o "$pr" \
    --epw "$root/data/weather/chicago_ohare_tmy3_weekly.epw" --sun-bins-deg 1 --sky-samples 1024 \
    --resolution 240 200 --seed 1 --quiet
# A print in the most lightfast of the watercolour pigments (cyan: 200 years to a
# just-noticeable fade at 50 lx of LED) behind the window glass, its year repeated; 0.58 of
# the baker's broadband sunlight lies in the band a dose counts
"$texgen" forecast --material cyan --rates watercolour \
    --exposure "$pr/exposure.exr" --scale 0.58 --lamp D65 \
    --uv-filter "$root/data/filters/window_glass.csv" --after 5 --preview -o "$pr"

# The forecast on the print, as glTF (a variant per map) and in the browser viewer
"$texgen" export "$pr" -o "$pr/print_forecast.glb" --quiet
"$texgen" view "$pr/print_forecast.glb" -o "$root/out/viewer/print_forecast"

# ---- The newspaper restored --------------------------------------------------------------
# A 0.5 m page folded in quarters for a June day, then in half for the next (as
# samples/fading does for figure 1); its faded base colour, as export writes it for glTF,
# restored with the doses: the lignin's yellowing is undone; the tint ("newsprint_other") has
# faded to nothing in the sun, so it keeps the material's amount.
rs="$out/restored"
mkdir -p "$rs"
"$texgen" mesh plane --size 0.5 -o "$rs/page.obj"
box "$rs/fold_quarters_a.obj" -0.26 0.0 0.002 0.006 -0.26 0.26
box "$rs/fold_quarters_b.obj" 0.0 0.26 0.002 0.006 0.0 0.26
box "$rs/fold_half.obj" -0.26 0.26 0.002 0.006 0.0 0.26
sun=(--latitude 43.47 --longitude -80.54 --timezone -5 --start 2026-06-21 --end 2026-06-22
     --sky clear --sun-bins-deg 2 --sky-samples 64 --resolution 128 --seed 1 --quiet)
"$texgen" exposure --mesh "$rs/page.obj" --occluder "$rs/fold_quarters_a.obj" \
    --occluder "$rs/fold_quarters_b.obj" -o "$rs/quarters" "${sun[@]}"
"$texgen" exposure --mesh "$rs/page.obj" --occluder "$rs/fold_half.obj" -o "$rs/half" "${sun[@]}"
"$texgen" fade --exposure "$rs/quarters/exposure.exr" --exposure "$rs/half/exposure.exr" \
    --scale 0.58 --material newsprint_free --out "$rs/faded" --quiet
"$texgen" export "$rs/faded" --separate -o "$rs/faded.gltf" --quiet
"$texgen" restore --image "$rs/faded_faded_base_color.png" --material newsprint_free \
    --dose-map "$rs/faded/dose.exr" --colorants lignin -o "$rs"
oiiotool "$rs/faded_faded_base_color.png" "$rs/restored.png" "$rs/confidence.png" \
    --mosaic:pad=8 3x1 -o "$rs/side_by_side.png"
echo "conservation: wrote $out"

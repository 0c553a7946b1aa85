#!/usr/bin/env bash
# samples/fading: light-induced fading (Kimmel et al. 2013) with patina-texgen fade and the
# spectral_km shader.
#   samples/fading/fading.sh [BUILD_DIR]     (default: build)
# Writes into out/fading/:
#   fig09_newsprint.png ... fig13_cork.png   reflectance over a week under the fluorescent
#                                            lamp (F11 at an assumed 100 W/m^2), like the
#                                            paper's figures 9-13
#   newspaper/                               figure 1: a page folded in quarters for a day,
#                                            then in half for a day, in June sun; unfolded,
#                                            its quarters have yellowed differently
#   board/                                   figure 18: a cork board whose papers were
#                                            moved between three exposures
#   cmy/                                     figure 15: seven C/M/Y mixtures faded with the
#                                            four rate sets of Table V
#   newspaper.png, board.png, cmy.png        the renders (patina-render + spectral_km)
# and out/export/newspaper.glb: the newspaper unexposed, after one day and after two, as a
# glTF asset with a material variant per day.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
out="$root/out/fading"
texgen="$build/bin/patina-texgen"
render="$build/bin/patina-render"
mkdir -p "$out"

# box FILE x0 x1 y0 y1 z0 z1: an axis-aligned box as an OBJ (samples/lib/obj.sh)
source "$root/samples/lib/obj.sh"

# ---- Figures 9-13: reflectance over 0h, 6h, 1d, 7d under the lamp -------------------------
# The paper does not give the lamp's irradiance at 5/8"; 100 W/m^2 over 300-830 nm is
# assumed: 7 days = 6.048e7 J/m^2.
week=6.048e7
for m in "09:newsprint" "10:congo_red" "11:toluidine_blue_o" "13:cork"; do
    fig=${m%%:*}; material=${m#*:}
    "$texgen" fade --dose $week --duration 7d --illuminant F11 --material "$material" \
        --entries 128 --out "$out/lamp/$material" --plot "$out/fig${fig}_${material}.png" --quiet \
        --plot-title "$material under F11, 100 W/m^2 (figure $fig)"
done

# ---- Figure 1: the newspaper folded in quarters ------------------------------------------
# A 0.5 m page (u along +x, v along -z). Folded in quarters, only the quarter x > 0, z < 0
# faces the sky: the folds of paper lie over the other three. Folded in half, the half
# z < 0 is open. Each arrangement is one clear June day at Waterloo, Ontario.
np="$out/newspaper"
mkdir -p "$np"
"$texgen" mesh plane --size 0.5 -o "$np/page.obj"
box "$np/fold_quarters_a.obj" -0.26 0.0 0.002 0.006 -0.26 0.26
box "$np/fold_quarters_b.obj" 0.0 0.26 0.002 0.006 0.0 0.26
box "$np/fold_half.obj" -0.26 0.26 0.002 0.006 0.0 0.26
sun=(--latitude 43.47 --longitude -80.54 --timezone -5 --start 2026-06-21 --end 2026-06-22
     --sky clear --sun-bins-deg 2 --sky-samples 64 --resolution 256 --seed 1 --quiet)
"$texgen" exposure --mesh "$np/page.obj" --occluder "$np/fold_quarters_a.obj" \
    --occluder "$np/fold_quarters_b.obj" -o "$np/quarters" "${sun[@]}"
"$texgen" exposure --mesh "$np/page.obj" --occluder "$np/fold_half.obj" -o "$np/half" "${sun[@]}"
# About 58% of the sun's energy falls within the 300-830 nm band a dose counts (a 5778 K
# black body: 0.575): --scale 0.58 turns the broadband exposure into the band's dose.
"$texgen" fade --exposure "$np/quarters/exposure.exr" --exposure "$np/half/exposure.exr" \
    --scale 0.58 --material newsprint --out "$np/after" --plot "$out/newspaper_curves.png" \
    --plot-title "newsprint in June sun (figure 1)" --quiet
"$texgen" fade --dose 0 --material newsprint --out "$np/before" --quiet
# The page after the first day alone, and the three stages as one glTF asset on the page's
# mesh, a variant per day (0 d, 1 d, 2 d).
"$texgen" fade --exposure "$np/quarters/exposure.exr" --scale 0.58 --material newsprint \
    --out "$np/day1" --quiet
mkdir -p "$root/out/export"
"$texgen" export "$np/before" "$np/day1" "$np/after" -o "$root/out/export/newspaper.glb" --quiet

# ---- Figure 18: a cork board with papers moved between exposures -------------------------
# A 0.8 m cork board lying in the open for three periods of 12 overcast hours, with sheets
# (boxes 2 mm above the cork) pinned and taken down between them, as in figure 18: sheet A
# stays all along, B is taken down after two periods, C goes up for the last one and D is
# there for the first only.
bd="$out/board"
mkdir -p "$bd"
"$texgen" mesh plane --size 0.8 -o "$bd/board.obj"
box "$bd/sheet_a.obj" -0.30 -0.09 0.002 0.004 -0.30 0.0
box "$bd/sheet_b.obj" 0.05 0.35 0.002 0.004 -0.35 -0.14
box "$bd/sheet_c.obj" -0.20 0.10 0.002 0.004 0.10 0.31
box "$bd/sheet_d.obj" 0.17 0.33 0.002 0.004 0.02 0.28
sun_b=(--latitude 43.47 --longitude -80.54 --timezone -5 --start 2026-05-01 --end 2026-05-02
       --sky overcast --sun-bins-deg 2 --sky-samples 64 --resolution 256 --seed 1 --quiet)
sheets=("a b d" "a b" "a c")
for k in 1 2 3; do
    occluders=()
    for s in ${sheets[$((k - 1))]}; do occluders+=(--occluder "$bd/sheet_$s.obj"); done
    "$texgen" exposure --mesh "$bd/board.obj" "${occluders[@]}" -o "$bd/period_$k" "${sun_b[@]}"
done
"$texgen" fade --exposure "$bd/period_1/exposure.exr" --exposure "$bd/period_2/exposure.exr" \
    --exposure "$bd/period_3/exposure.exr" --duration 12h --scale 0.58 --material cork \
    --out "$bd/after" --plot "$out/board_curves.png" --plot-title "cork board (figure 18)" --quiet
"$texgen" fade --dose 0 --material cork --out "$bd/before" --quiet

# ---- Figure 15: C, M, Y mixtures faded with Table V's four rate sets ----------------------
# Table V's rates with these absorptions fade a surface in ~10-100 J/m^2 of D65 (see
# shaders/fade/pigments.toml), so the figure's 4.365e7 J/m^2 is scaled by 2e-7: the same
# as dividing every rate by 5e6, which keeps the rows' ratios.
cmy="$out/cmy"
mkdir -p "$cmy"
mixtures=(cyan magenta yellow cyan_magenta cyan_yellow magenta_yellow cyan_magenta_yellow)
for m in "${mixtures[@]}"; do
    "$texgen" fade --dose 0 --material "$m" --out "$cmy/row0_$m" --entries 4 --quiet
    for r in 1 2 3 4; do
        "$texgen" fade --dose 4.365e7 --scale 2e-7 --illuminant D65 --material "$m" \
            --rates "table_v_row$r" --out "$cmy/row${r}_$m" --entries 16 --quiet
    done
done

# The swatches' scene: rows = unfaded, Table V rows 1-4; columns = the mixtures
{
    cat <<EOF
# Generated by samples/fading/fading.sh: figure 15's swatches (rows: unfaded, then Table V
# rows 1-4 from the top; columns: ${mixtures[*]}).
[film]
width = 700
height = 520
spp = 16
seed = 1
max_depth = 3

[camera]
from = [0.0, 0.0, 10.0]
to = [0.0, 0.0, 0.0]
fov_deg = 40

[environment]
color = [1.0, 1.0, 1.0]
colorspace = "lin_rec709"
intensity = 1.0

[output]
file = "../cmy.exr"
display = "sRGB"
view = "ACES 1.0 - SDR Video"
EOF
    for r in 0 1 2 3 4; do
        for c in "${!mixtures[@]}"; do
            m=${mixtures[$c]}
            x=$(awk "BEGIN { print ($c - 3) * 1.0 }")
            y=$(awk "BEGIN { print (2 - $r) * 1.0 - ($r > 0 ? 0.25 : 0) }")
            cat <<EOF

[[shader]]
name = "r${r}_$m"
type = "spectral_km"
fade = "row${r}_$m/fade.toml"

[[object]]
shape = "box"
center = [$x, $y, 0.0]
size = [0.9, 0.9, 0.05]
bsdf = "r${r}_$m"
EOF
        done
    done
} > "$cmy/scene.toml"

# ---- Renders ------------------------------------------------------------------------------
"$render" "$here/newspaper.toml" --output "$out/newspaper.exr" --quiet
"$render" "$here/board.toml" --output "$out/board.exr" --quiet
"$render" "$cmy/scene.toml" --output "$out/cmy.exr" --quiet
echo "wrote out/fading/: fig09-13 plots, newspaper.png (figure 1), board.png (figure 18), cmy.png (figure 15)"

#!/usr/bin/env bash
# Noise against weathering in a rendered time series (samples/stone/stone.sh):
#   measure.sh SUBJECT VIEW X0 Y0 X1 Y1 STEP_DIR...
# Each STEP_DIR holds VIEW.s1.png and VIEW.s2.png, two renders of the same picture with
# different seeds, and VIEW.png, the picture of their mean, all display-referred (sRGB
# through the ACES 1.0 SDR view, what a viewer sees; in the scene-linear EXRs a few
# bright paths through a backlit statue would dominate every statistic). Over the pixel box
# [X0, X1) x [Y0, Y1) (the stone), in luma Y' (Rec. 709 weights, values in [0, 1]):
#   noise of a picture = rms(s1 - s2) / 2, the per-pixel standard deviation of the mean;
#   change of a step   = the rms per-pixel difference D = mean_k - mean_k+1 between
#                        consecutive pictures, less the part noise accounts for: with
#                        D_s = s_k - s_k+1 per seed (the same seed's noise is correlated
#                        from step to step), the noise of D is v = rms(D_1 - D_2) / 2, and
#                        the change is sqrt(rms(D)^2 - v^2).
# A change larger than the pictures' noise is one they show pixel by pixel.
set -euo pipefail
label="$1 $2" view="$2" x0="$3" y0="$4" x1="$5" y1="$6"
shift 6
box="$((x1 - x0))x$((y1 - y0))+${x0}+${y0}"
luminance="--chsum:weight=0.2126,0.7152,0.0722"

# rms A B: the rms over the box of the luminance of A - B
rms() {
    oiiotool "$1" "$2" --sub $luminance --cut "$box" --printstats |
        awk '/Stats Avg:/{a=$3} /Stats StdDev:/{s=$3} END{printf "%.5f", sqrt(a*a+s*s)}'
}
# rms_of_difference A1 B1 A2 B2: the rms over the box of (A1 - B1) - (A2 - B2), and of
# their mean ((A1 - B1) + (A2 - B2)) / 2
rms_of_differences() {
    local d1 d2
    d1=$(oiiotool "$1" "$2" --sub "$3" "$4" --sub --sub $luminance --cut "$box" --printstats |
        awk '/Stats Avg:/{a=$3} /Stats StdDev:/{s=$3} END{printf "%.5f", sqrt(a*a+s*s)}')
    d2=$(oiiotool "$1" "$2" --sub "$3" "$4" --sub --add --mulc 0.5 $luminance --cut "$box" \
            --printstats |
        awk '/Stats Avg:/{a=$3} /Stats StdDev:/{s=$3} END{printf "%.5f", sqrt(a*a+s*s)}')
    echo "$d1 $d2"
}
# mean A: the mean R G B over the box
mean() {
    oiiotool "$1" --cut "$box" --printstats | awk '/Stats Avg:/{printf "%.4f %.4f %.4f", $3, $4, $5}'
}

previous="" previous_noise=""
for dir in "$@"; do
    step="$dir/$view"
    name="$(basename "$dir")"
    noise=$(awk -v d="$(rms "$step.s1.png" "$step.s2.png")" 'BEGIN{printf "%.5f", d / 2}')
    read -r r g b <<< "$(mean "$step.png")"
    printf '%s %s: mean R'"'"'G'"'"'B'"'"' %.4f %.4f %.4f (B/R %.3f), noise %.4f\n' "$label" "$name" \
        "$r" "$g" "$b" "$(awk -v r="$r" -v b="$b" 'BEGIN{print b / r}')" "$noise"
    if [ -n "$previous" ]; then
        read -r spread d <<< "$(rms_of_differences "$previous.s1.png" "$step.s1.png" \
                                                    "$previous.s2.png" "$step.s2.png")"
        awk -v l="$label" -v from="$(basename "$(dirname "$previous")")" -v to="$name" \
            -v d="$d" -v v="$spread" -v n1="$previous_noise" -v n2="$noise" 'BEGIN {
                v = v / 2; c2 = d * d - v * v; c = c2 > 0 ? sqrt(c2) : 0;
                n = n1 > n2 ? n1 : n2;
                printf "%s %s -> %s: change %.4f, noise %.4f, change/noise %.2f%s\n",
                       l, from, to, c, n, c / n, (c > n ? "" : "  (NOT above the noise)") }'
    fi
    previous="$step" previous_noise="$noise"
done

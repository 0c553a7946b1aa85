#!/usr/bin/env bash
# bench/export_vs_grow.sh [BUILD_DIR]: exporting a time series as one .glb against growing it.
# Grows the urban strip of Dorsey & Hanrahan 1996 §5.1 over 0-30 years in six-year steps at
# SIZE² texels (default 2048) with `patina-texgen patina`, then exports the six steps as one
# glTF asset with `patina-texgen export` (flatten per step, PNG maps, variants). Prints both
# wall-clock times (best of RUNS, default 1) and the ratio export / grow: the target is ≤ 0.5
# (exporting costs less than half of what growing did).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
size="${SIZE:-2048}"
texgen="$build/bin/patina-texgen"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/export_vs_grow.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

# shellcheck source=lib/best_time.sh
source "$here/lib/best_time.sh"

grow=$(best "$texgen" patina "$root/samples/copper_strips/urban.patina" -o "$tmp/urban" \
       --resolution "$size" --times 0,6,12,18,24,30 --seed 1 --quiet --no-preview)
export_s=$(best "$texgen" export "$tmp/urban" -o "$tmp/urban.glb" --quiet)
bytes=$(stat -c %s "$tmp/urban.glb")
echo "urban strip, 6 steps at ${size}²: grow ${grow} s, export ${export_s} s (${bytes} bytes)"
echo "$export_s $grow" | awk '{printf "ratio export / grow %.2f  (target <= 0.5)\n", $1 / $2}'

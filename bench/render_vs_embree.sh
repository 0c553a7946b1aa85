#!/usr/bin/env bash
# Patina's path tracer against Embree's own tutorial path tracer (`pathtracer` from Debian's
# embree-tools) on the same OBJ scene in one run: a ~69k-triangle statue on a ground plane
# (written by bench_make_bench_scene), diffuse (albedo 0.8), a uniform white environment,
# 512x512, the same samples per pixel and the same maximum path length. Each renderer runs
# RUNS times (default 5: the host's noise moves single runs by 10-20 %); the fastest render
# counts. Prints seconds and samples/s
# (width * height * spp / render seconds) of both and the ratio patina / embree, and for
# reference Patina with [render] sample_uniform_sky = true (the uniform sky light-sampled
# as well, a shadow ray per hit like the tutorial's loop; patina-render's default leaves
# it to BSDF sampling, as pbrt-v4 does).
#
#   bench/render_vs_embree.sh [--rays] [--keep DIR]
#
#   --rays       also count the rays each renderer traces per sample (a second, untimed pair
#                of runs at 128x128 with a 30-line LD_PRELOAD shim around rtcIntersect1,
#                rtcIntersect1M (patina-render's camera rays) and
#                rtcOccluded1, compiled with cc into the temporary folder)
#   --keep DIR   copy the scene, Patina's EXR and PNG and one Embree frame (PPM) into DIR
#
# Environment: PATINA_BUILD_DIR (default build/, as made by ./test.sh; nothing is built
# here), SPP (16), SIZE (512), MAX_DEPTH (8), THREADS (2), RUNS (5), PATHTRACER (the
# embree-tools binary, default `pathtracer` on PATH).
#
# What is timed (render only, for both; scene loading and BVH builds are excluded):
#   patina-render  the "elapsed" of its last progress line: the wall time of render_region,
#                  from the first tile to the last, after plugins, the OBJ and the BVH are
#                  loaded and before the EXR is written; printed to 0.01 s.
#   pathtracer     `--benchmark 1 1 --legacy`: one warm-up frame (the tutorial builds its
#                  BVH inside the first frame), then one frame timed with wall-clock
#                  getSeconds() around the render call, printed as fps (BENCHMARK_RENDER_MAX);
#                  one frame is width x height pixels x --spp samples.
# The whole-process wall time of every run is printed too (Embree's includes two frames).
#
# Path length: Embree's --max-path-length N runs its loop N times: N closest-hit rays, each
# hit shaded with a light sample (shadow ray); "1 = primary + shadow". Patina's max_depth N
# shades hits at depths 0..N-1 (light sample + BSDF sample each) and traces the last BSDF
# ray to collect the environment with MIS. Both estimate paths of at most N scattering
# events; Patina traces one more closest-hit ray on the paths that reach the limit.
#
# A benchmark never gates: this script always exits 0.
set -uo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
build=${PATINA_BUILD_DIR:-build}
[[ $build = /* ]] || build="$root/$build"
spp=${SPP:-16}
size=${SIZE:-512}
max_depth=${MAX_DEPTH:-8}
threads=${THREADS:-2}
runs=${RUNS:-5}
pathtracer=${PATHTRACER:-pathtracer}
count_rays=0
keep=""

while [ $# -gt 0 ]; do
  case "$1" in
    --rays) count_rays=1 ;;
    --keep) keep=${2:-}; shift ;;
    -h|--help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0"; exit 0 ;;
    *) echo "render_vs_embree: unknown argument '$1' (see --help)" >&2; exit 0 ;;
  esac
  shift
done

say() { echo "render_vs_embree: $*" >&2; }

patina="$build/bin/patina-render"
generator="$build/bin/bench_make_bench_scene"
for exe in "$patina" "$generator"; do
  if [ ! -x "$exe" ]; then
    say "$exe not found: build first (./test.sh, or set PATINA_BUILD_DIR)"
    exit 0
  fi
done
if ! command -v "$pathtracer" >/dev/null 2>&1; then
  say "Embree's tutorial path tracer '$pathtracer' not found: apt-get install embree-tools"
  exit 0
fi

tmp=$(mktemp -d "${TMPDIR:-/tmp}/render_vs_embree.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

# --- The scene: one OBJ (statue + ground, one diffuse MTL material) for both renderers.
triangles=$("$generator" "$tmp/statue.obj") || { say "scene generator failed"; exit 0; }

# One camera for both: pinhole, vertical field of view, square image.
cam_from=(0 2.4 8)
cam_to=(0 0.9 0)
fov=30

cat >"$tmp/scene.toml" <<EOF
# bench/render_vs_embree.sh: the statue under a uniform white sky.
[film]
width = $size
height = $size
spp = $spp
seed = 1
max_depth = $max_depth
wavelengths = 4
integrator = "mis"

# Embree's traversal without RTC_SCENE_FLAG_ROBUST, as the tutorial builds its scene (it has
# no option for the flag); patina-render's default is robust = true.
[render]
robust = false

[camera]
from = [${cam_from[0]}.0, ${cam_from[1]}, ${cam_from[2]}.0]
to = [${cam_to[0]}.0, ${cam_to[1]}, ${cam_to[2]}.0]
up = [0.0, 1.0, 0.0]
fov_deg = $fov

[environment]
color = [1.0, 1.0, 1.0]

[output]
file = "patina.exr"
png = true

[[shader]]
name = "diffuse"
type = "lambert"
reflectance = 0.8

[[object]]
mesh = "statue.obj"
bsdf = "diffuse"
EOF

patina_args=("$tmp/scene.toml" --threads "$threads")
# For reference, not for the target: the uniform sky light-sampled as well (over the sphere,
# with MIS), as patina-render did before 2026-11-27 and as the tutorial's loop is shaped (one
# shadow ray per hit). By default patina-render leaves a uniform sky to BSDF sampling
# (pbrt-v4 §12.5.1), which is less noisy per sample and traces no shadow rays for it.
sed 's/^robust = false$/robust = false\nsample_uniform_sky = true/' "$tmp/scene.toml" >"$tmp/scene_ls.toml"
patina_ls_args=("$tmp/scene_ls.toml" --threads "$threads")
embree_args=(-i "$tmp/statue.obj"
             --vp "${cam_from[@]}" --vi "${cam_to[@]}" --vu 0 1 0 --fov "$fov"
             --size "$size" "$size" --spp "$spp" --max-path-length "$max_depth"
             --ambientlight 1 1 1 --threads "$threads")

now_ns() { date +%s%N; }
# seconds between two now_ns values
span() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", (b - a) / 1e9 }'; }
# the smaller of two numbers ("" counts as missing)
smaller() { awk -v a="$1" -v b="$2" 'BEGIN { if (a == "") print b; else if (b == "" || a + 0 <= b + 0) print a; else print b }'; }

best_patina="" best_patina_proc="" best_embree="" best_embree_proc="" embree_mrays=""
best_patina_ls=""

# The runs alternate (patina, embree, patina, embree, ...) so that a load that comes and
# goes on the machine falls on both alike.
# $1 the run's number; with $2 = ls, the scene that light-samples the uniform sky.
run_patina() {
  local t0 t1 sec
  local -a args=("${patina_args[@]}")
  [ "${2:-}" = ls ] && args=("${patina_ls_args[@]}")
  t0=$(now_ns)
  if ! "$patina" "${args[@]}" 2>"$tmp/patina.err" >/dev/null; then
    say "patina-render failed:"; tr '\r' '\n' <"$tmp/patina.err" | tail -3 >&2; return 1
  fi
  t1=$(now_ns)
  # Its last progress line: "render: 100.0%  elapsed 2.31s  ETA 0.0s".
  sec=$(tr '\r' '\n' <"$tmp/patina.err" | sed -n 's/^render: 100.0% *elapsed \([0-9.]*\)s.*/\1/p' | tail -1)
  [ -n "$sec" ] || { say "patina-render printed no elapsed time"; return 1; }
  if [ "${2:-}" = ls ]; then
    say "run $1: patina-render, sky light-sampled too, render ${sec} s"
    best_patina_ls=$(smaller "$best_patina_ls" "$sec")
    return 0
  fi
  say "run $1: patina-render render ${sec} s, process $(span "$t0" "$t1") s"
  best_patina=$(smaller "$best_patina" "$sec")
  best_patina_proc=$(smaller "$best_patina_proc" "$(span "$t0" "$t1")")
}

# Embree's tutorial: one warm-up frame (it builds the BVH in its first frame), one timed frame.
run_embree() {
  local t0 t1 fps sec
  t0=$(now_ns)
  if ! "$pathtracer" "${embree_args[@]}" --benchmark 1 1 --legacy >"$tmp/embree.out" 2>&1; then
    say "pathtracer failed:"; tail -3 "$tmp/embree.out" >&2; return 1
  fi
  t1=$(now_ns)
  fps=$(sed -n 's/^BENCHMARK_RENDER_MAX \([0-9.eE+-]*\)/\1/p' "$tmp/embree.out")
  [ -n "$fps" ] || { say "pathtracer printed no BENCHMARK_RENDER_MAX"; return 1; }
  sec=$(awk -v f="$fps" 'BEGIN { printf "%.4f", 1 / f }')
  say "run $1: pathtracer frame ${sec} s, process $(span "$t0" "$t1") s (2 frames)"
  if [ "$(smaller "$best_embree" "$sec")" = "$sec" ]; then
    embree_mrays=$(sed -n 's/^BENCHMARK_RENDER_MRAYPS_MAX \([0-9.eE+-]*\)/\1/p' "$tmp/embree.out")
  fi
  best_embree=$(smaller "$best_embree" "$sec")
  best_embree_proc=$(smaller "$best_embree_proc" "$(span "$t0" "$t1")")
}

load_before=$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo "?")
for ((r = 1; r <= runs; r++)); do
  run_patina "$r"
  run_embree "$r"
  run_patina "$r" ls
done

# --- The table.
samples=$((size * size * spp))
rate() { [ -n "$1" ] && awk -v n="$samples" -v s="$1" 'BEGIN { printf "%.3f", n / s / 1e6 }'; }
patina_rate=$(rate "$best_patina")
patina_ls_rate=$(rate "$best_patina_ls")
embree_rate=$(rate "$best_embree")

echo
echo "render_vs_embree: 1-minute load average before the runs: $load_before on $(nproc) cores" \
     "(other jobs on the machine inflate both wall times)"
echo "render_vs_embree: statue.obj ($triangles triangles with the ground), ${size}x${size}, $spp spp," \
     "max path length $max_depth, diffuse 0.8, uniform white environment," \
     "$threads thread$([ "$threads" = 1 ] || echo s), best of $runs"
printf '%-44s %10s %10s %14s\n' "renderer" "render s" "process s" "M samples/s"
printf '%-44s %10s %10s %14s\n' "patina-render (mis, 4 hero wavelengths)" \
  "${best_patina:-n/a}" "${best_patina_proc:-n/a}" "${patina_rate:-n/a}"
printf '%-44s %10s %10s %14s\n' "embree pathtracer tutorial (RGB)" \
  "${best_embree:-n/a}" "${best_embree_proc:-n/a}" "${embree_rate:-n/a}"
if [ -n "$patina_rate" ] && [ -n "$embree_rate" ]; then
  awk -v p="$patina_rate" -v e="$embree_rate" \
    'BEGIN { printf "ratio patina / embree (samples/s): %.2f   (target >= 1.2)\n", p / e }'
  awk -v p="$patina_rate" \
    'BEGIN { printf "patina traces 4 hero wavelengths per sample, every BSDF call through the plugin C ABI: %.2f M wavelength-samples/s\n", 4 * p }'
fi
[ -n "$embree_mrays" ] && echo "embree reports $embree_mrays M rays/s (closest-hit + shadow rays) for its fastest frame"
if [ -n "$patina_ls_rate" ] && [ -n "$embree_rate" ]; then
  awk -v p="$patina_ls_rate" -v e="$embree_rate" -v s="$best_patina_ls" \
    'BEGIN { printf "for reference: patina-render with [render] sample_uniform_sky = true (a shadow ray per hit, as the tutorial): %s s, %.3f M samples/s, ratio %.2f\n", s, p, p / e }'
fi

# --- Optional: rays per sample of both (untimed), by interposing Embree's ray queries.
if [ "$count_rays" = 1 ]; then
  cc=$(command -v cc || command -v gcc || true)
  if [ -z "$cc" ]; then
    say "--rays: no C compiler found"
  else
    cat >"$tmp/raycount.c" <<'EOF'
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdatomic.h>
#include <stdio.h>
typedef void (*query_fn)(void*, void*, void*);
static atomic_ulong n_intersect, n_occluded;
void rtcIntersect1(void* scene, void* context, void* rayhit)
{
    static query_fn real;
    if (!real) real = (query_fn)dlsym(RTLD_NEXT, "rtcIntersect1");
    atomic_fetch_add_explicit(&n_intersect, 1, memory_order_relaxed);
    real(scene, context, rayhit);
}
typedef void (*stream_fn)(void*, void*, void*, unsigned, size_t);
void rtcIntersect1M(void* scene, void* context, void* rayhits, unsigned m, size_t stride)
{
    static stream_fn real;
    if (!real) real = (stream_fn)dlsym(RTLD_NEXT, "rtcIntersect1M");
    atomic_fetch_add_explicit(&n_intersect, m, memory_order_relaxed);
    real(scene, context, rayhits, m, stride);
}
void rtcOccluded1(void* scene, void* context, void* ray)
{
    static query_fn real;
    if (!real) real = (query_fn)dlsym(RTLD_NEXT, "rtcOccluded1");
    atomic_fetch_add_explicit(&n_occluded, 1, memory_order_relaxed);
    real(scene, context, ray);
}
__attribute__((destructor)) static void report(void)
{
    fprintf(stderr, "\nRAYCOUNT %lu %lu\n", (unsigned long)n_intersect, (unsigned long)n_occluded);
}
EOF
    if "$cc" -O2 -shared -fPIC -o "$tmp/raycount.so" "$tmp/raycount.c" -ldl; then
      small=128
      n=$((small * small * spp))
      per_sample() { tr '\r' '\n' <"$1" | awk -v n="$n" '$1 == "RAYCOUNT" { printf "%.3f closest-hit + %.3f shadow = %.3f rays/sample\n", $2 / n, $3 / n, ($2 + $3) / n }' | tail -1; }
      LD_PRELOAD="$tmp/raycount.so" "$patina" "${patina_args[@]}" --resolution "$small" "$small" \
        --quiet --output "$tmp/rays.exr" >/dev/null 2>"$tmp/patina.rays"
      # -o renders exactly one frame after the scene is built.
      LD_PRELOAD="$tmp/raycount.so" "$pathtracer" "${embree_args[@]}" --size "$small" "$small" \
        -o "$tmp/rays.ppm" >/dev/null 2>"$tmp/embree.rays"
      echo "rays per sample (${small}x${small}, $spp spp, same view):"
      echo "  patina-render: $(per_sample "$tmp/patina.rays")"
      echo "  embree:        $(per_sample "$tmp/embree.rays")"
    fi
  fi
fi

if [ -n "$keep" ]; then
  mkdir -p "$keep"
  cp "$tmp/scene.toml" "$tmp/statue.obj" "$tmp/statue.mtl" "$tmp"/patina.exr "$tmp"/patina.png "$keep"/ 2>/dev/null
  "$pathtracer" "${embree_args[@]}" -o "$keep/embree.ppm" >/dev/null 2>&1
  say "kept the scene and both images in $keep"
fi

echo "commands:"
echo "  patina-render ${patina_args[*]}" | sed "s|$tmp/||g"
echo "  pathtracer ${embree_args[*]} --benchmark 1 1 --legacy" | sed "s|$tmp/||g"
exit 0

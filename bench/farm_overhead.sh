#!/usr/bin/env bash
# bench/farm_overhead.sh [BUILD_DIR]: what rendering through Slurm costs over one process.
# Renders samples/basic/scene.toml at SPP samples per pixel (default 144, about 30 s on the
# development machine) in one process, then as a 4-tile job on a one-node Slurm cluster
# (tests/farm/slurm_cluster.sh: run as root, with Debian's slurm-wlm and munge) through
# `patina-farm submit`, waiting until its merge job is done; checks that the merged frame is
# bitwise the one-process render, and prints both wall-clock times and the farm's overhead
# (scheduling, four scene loads, the merge) as farm / one process − 1: the aim is ≤ 10 %.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
spp="${SPP:-144}"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/farm_overhead.XXXXXX")
cluster="$tmp/cluster"
trap '"$root/tests/farm/slurm_cluster.sh" stop "$cluster" >/dev/null 2>&1 || true; rm -rf "$tmp"' EXIT
"$root/tests/farm/slurm_cluster.sh" start "$cluster" >/dev/null
export SLURM_CONF="$cluster/slurm.conf"
scene="$root/samples/basic/scene.toml"

now() { date +%s.%N; }
t0=$(now)
"$build/bin/patina-render" "$scene" --spp "$spp" --quiet --output "$tmp/one_process.exr"
t1=$(now)
read -r array merge < <("$build/bin/patina-farm" submit "$scene" --spp "$spp" --tiles 4 ${FARM_OPTIONS:-} \
                        --job "$tmp/job")
while [[ -n "$(squeue -h -j "$array,$merge" -o %i 2>/dev/null)" ]]; do sleep 0.1; done
t2=$(now)
if ! oiiotool "$tmp/one_process.exr" "$tmp/job/frames/frame.0000.exr" --diff --fail 0 \
       --failpercent 0 --warn 0 | grep -q PASS; then
  echo "the farm's frame differs from the one-process render" >&2
  exit 1
fi
echo "$t0 $t1 $t2" | awk -v spp="$spp" '{
  one = $2 - $1; farm = $3 - $2
  printf "basic scene at %d spp: one process %.1f s, 4 tiles through Slurm %.1f s (bitwise the same)\n", spp, one, farm
  printf "farm overhead %.1f %%  (aim <= 10 %%)\n", 100 * (farm / one - 1)
}'

#!/usr/bin/env bash
# Builds the libFuzzer harnesses of fuzz/ with clang into $PATINA_FUZZ_BUILD_DIR (default
# build-fuzz/) and runs each for SECONDS (default 180) from its committed corpus
# (fuzz/corpus/<name>/). New inputs go to a scratch corpus; with --merge, the ones that add
# coverage are merged back into the committed corpus (kept small: -max_len 4096).
# Usage: scripts/fuzz.sh [SECONDS] [--merge] [NAME...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=180
merge=0
names=()
for a in "$@"; do
  case "$a" in
    --merge) merge=1 ;;
    ''|*[!0-9]*) names+=("$a") ;;
    *) seconds=$a ;;
  esac
done
[ ${#names[@]} -eq 0 ] && names=(script_parser epw stack_manifest scene)
PATINA_BOOTSTRAP_EXTRA="clang libclang-rt-14-dev" ./scripts/bootstrap.sh
./scripts/build.sh >/dev/null   # the bundled plugins and static libraries of the scene fuzzer
main=$(pwd)/${PATINA_BUILD_DIR:-build}
build=${PATINA_FUZZ_BUILD_DIR:-build-fuzz}
CC=clang CXX=clang++ cmake -S fuzz -B "$build" -G Ninja -DPATINA_BUILD_DIR="$main" >/dev/null
cmake --build "$build" -j "$(nproc)"
# As in sanitize.sh (and for the same third-party reasons, scripts/sanitize/*.supp).
export ASAN_OPTIONS="new_delete_type_mismatch=0"
export LSAN_OPTIONS="suppressions=$(pwd)/scripts/sanitize/lsan.supp:print_suppressions=0"
for name in "${names[@]}"; do
  scratch=$(mktemp -d)
  echo "fuzz: $name for $seconds s" >&2
  start=$(date +%s)
  "$build/${name}_fuzz" -max_total_time="$seconds" -max_len=4096 -timeout=10 \
    -rss_limit_mb=4096 -print_final_stats=1 "$scratch" "fuzz/corpus/$name" 2>&1 |
    grep -E "^(#[0-9]+.*DONE|stat::number_of_executed_units|stat::peak_rss_mb|==.*ERROR|SUMMARY)" || true
  status=${PIPESTATUS[0]}
  echo "fuzz: $name: exit $status after $(( $(date +%s) - start )) s" >&2
  if [ "$merge" = 1 ]; then
    "$build/${name}_fuzz" -merge=1 -max_len=4096 "fuzz/corpus/$name" "$scratch" >/dev/null 2>&1
  fi
  rm -rf "$scratch"
  [ "$status" -eq 0 ] || exit "$status"
done

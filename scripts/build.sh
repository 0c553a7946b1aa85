#!/usr/bin/env bash
# Installs what is missing and builds everything (Release, Ninja) into $PATINA_BUILD_DIR
# (default build/). Used by ./run.sh and ./test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/bootstrap.sh
build=${PATINA_BUILD_DIR:-build}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$(nproc)"

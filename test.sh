#!/usr/bin/env bash
# Installs what is missing, builds everything and runs every test through CTest.
set -euo pipefail
cd "$(dirname "$0")"
./scripts/build.sh
ctest --test-dir "${PATINA_BUILD_DIR:-build}" -j "$(nproc)" --output-on-failure

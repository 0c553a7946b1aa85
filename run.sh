#!/usr/bin/env bash
# Installs what is missing, builds, and renders the sample scene into out/.
set -euo pipefail
cd "$(dirname "$0")"
./scripts/bootstrap.sh
build=${PATINA_BUILD_DIR:-build}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$(nproc)"
mkdir -p out
"$build/bin/patina-render" samples/smoke/scene.toml --output out/smoke.exr "$@"
echo "wrote out/smoke.exr (scene-linear ACEScg) and out/smoke.png (sRGB display)"

#!/usr/bin/env bash
# Installs what is missing, builds, and renders samples/basic into out/.
set -euo pipefail
cd "$(dirname "$0")"
./scripts/bootstrap.sh
build=${PATINA_BUILD_DIR:-build}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$(nproc)"
mkdir -p out
"$build/bin/patina-render" samples/basic/scene.toml --output out/basic.exr "$@"
echo "wrote out/basic.exr (scene-linear ACEScg, with albedo, normal and depth AOVs) and out/basic.png (sRGB display)"

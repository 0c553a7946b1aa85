#!/usr/bin/env bash
# Installs what is missing, builds, and renders samples/basic into out/.
set -euo pipefail
cd "$(dirname "$0")"
./scripts/build.sh
mkdir -p out
"${PATINA_BUILD_DIR:-build}/bin/patina-render" samples/basic/scene.toml --output out/basic.exr "$@"
echo "wrote out/basic.exr (scene-linear ACEScg, with albedo, normal and depth AOVs) and out/basic.png (sRGB display)"

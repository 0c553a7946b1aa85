#!/usr/bin/env bash
# Installs what is missing, builds, renders samples/basic into out/, then bakes the texgen
# maps of the project's statue (samples/bake) and renders them.
set -euo pipefail
cd "$(dirname "$0")"
./scripts/build.sh
build="${PATINA_BUILD_DIR:-build}"
mkdir -p out
"$build/bin/patina-render" samples/basic/scene.toml --output out/basic.exr "$@"
echo "wrote out/basic.exr (scene-linear ACEScg, with albedo, normal and depth AOVs) and out/basic.png (sRGB display)"
samples/bake/bake.sh "$build"
echo "wrote out/bake/maps/ (texture stack + stack.toml) and out/bake.png (the maps on four statues)"

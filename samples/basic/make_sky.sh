#!/usr/bin/env bash
# Makes sky.exr, the sample's lat-long environment: a sky-blue zenith fading to a warm
# ground, with OpenImageIO's oiiotool (installed by scripts/bootstrap.sh).
set -euo pipefail
cd "$(dirname "$0")"
oiiotool --pattern fill:top=1.1,1.3,1.8:bottom=0.35,0.32,0.28 256x128 3 -d half -o sky.exr

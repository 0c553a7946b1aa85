#!/usr/bin/env bash
# bench/viewer_frame_time.sh [BUILD_DIR]: the viewer's frame time at 1280 x 720 in headless
# chromium (SwiftShader) for the urban strip's time series (D&H 1996 §5.1, six steps at
# SIZE², default 2048), and the time from opening the page to its first frame, each as a
# ratio against a bare three.js page showing the same .glb with its plain GLTFLoader and no
# blending or OCIO pass (bench/viewer_bare/). Aim: frame time <= 1.5 x the bare page's.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
size="${SIZE:-2048}"
frames="${FRAMES:-60}"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/viewer_bench.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
texgen="$build/bin/patina-texgen"

"$texgen" patina "$root/samples/copper_strips/urban.patina" --times 0,6,12,18,24,30 \
    --resolution "$size" --no-preview -q -o "$tmp/urban"
"$texgen" export "$tmp/urban" -o "$tmp/urban.glb" --quiet
"$texgen" view "$tmp/urban.glb" -o "$tmp/viewer" -q
mkdir -p "$tmp/bare"
cp "$tmp/viewer/data.js" "$here/viewer_bare/index.html" "$tmp/bare/"
NODE_PATH="$root/viewer/node_modules" "$root/viewer/node_modules/esbuild/bin/esbuild" \
    "$here/viewer_bare/bare.js" --bundle \
    --format=iife --minify --target=es2020 --log-level=warning --outfile="$tmp/bare/bare.js"

page="$root/tests/clients/viewer_page.mjs"
# The viewer in its default view at 3 years: between two steps, so every material mixes two.
node "$page" "$tmp/viewer" frames "$frames" "ACES 1.0 - SDR Video" 3 > "$tmp/viewer.json"
node "$page" "$tmp/bare" frames "$frames" > "$tmp/bare.json"
node - "$tmp/viewer.json" "$tmp/bare.json" "$size" "$(stat -c %s "$tmp/urban.glb")" <<'JS'
const fs = require('fs');
const [viewerFile, bareFile, size, bytes] = process.argv.slice(2);
const v = JSON.parse(fs.readFileSync(viewerFile)), b = JSON.parse(fs.readFileSync(bareFile));
const median = (a) => { const s = [...a].sort((x, y) => x - y); return s[Math.floor(s.length / 2)]; };
const fv = median(v.frameTimes), fb = median(b.frameTimes);
console.log(`urban strip, 6 steps at ${size}^2 (${(bytes / 1e6).toFixed(1)} MB .glb), 1280x720, chromium + SwiftShader`);
console.log(`frame time (median of ${v.frameTimes.length}): viewer ${fv.toFixed(1)} ms, bare page ${fb.toFixed(1)} ms: ratio ${(fv / fb).toFixed(2)} (aim <= 1.5)`);
console.log(`open to first frame: viewer ${v.openToFirstFrameMs} ms, bare page ${b.openToFirstFrameMs} ms: ratio ${(v.openToFirstFrameMs / b.openToFirstFrameMs).toFixed(2)}`);
JS

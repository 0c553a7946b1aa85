#!/usr/bin/env bash
# The outputs of ./run.sh as one hash per file, to show that a change of the code's layout
# changed no result: run before and after, then compare.
#   scripts/output_hashes.sh [OUT_DIR] > before.txt      (after ./run.sh at the old commit)
#   scripts/output_hashes.sh [OUT_DIR] > after.txt       (after ./run.sh at the new one)
#   diff before.txt after.txt                            (no output: bitwise the same)
# Images (EXR, PNG, JPEG, TIFF) are hashed by their pixels (oiiotool --hash: SHA-1 of the
# pixel data), so a header's software name or a timestamp does not count; OpenVDB files by
# their bytes with the random UUID every file gets blanked; TOML files by their content
# (parsed, keys sorted: a comment or the order of tables is no result); every other file
# by its bytes.
# Logs and the files that carry a time of day or a run time by design are left out, each
# named below with why.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="$(cd "${1:-$root/out}" && pwd)"

excluded() {
    case "$1" in
        *.log) return 0 ;;            # progress, timings
        */timing.toml) return 0 ;;    # wall-clock times of a run
        */timings.txt) return 0 ;;    # wall-clock times of the stone sample
        *.fbx) return 0 ;;            # Blender's FBX exporter stamps the time of writing
        */.patina-staging-*) return 0 ;;
    esac
    return 1
}

cd "$out"
find . -type f | LC_ALL=C sort | while IFS= read -r file; do
    excluded "$file" && continue
    case "${file,,}" in
        *.exr | *.png | *.jpg | *.jpeg | *.tif | *.tiff)
            hash="$(oiiotool --hash "$file" 2>/dev/null | sed -n 's/.*SHA-1: *//p' | tr '\n' ' ')"
            echo "$file pixels ${hash:-unreadable}" ;;
        *.vdb)
            echo "$file bytes-without-uuid $(python3 -c '
import hashlib, re, sys
data = re.sub(rb"[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}", b"0" * 36,
              open(sys.argv[1], "rb").read())
print(hashlib.sha256(data).hexdigest())' "$file")" ;;
        *.toml)
            echo "$file toml $(python3 -c '
import hashlib, json, sys, tomllib
content = json.dumps(tomllib.load(open(sys.argv[1], "rb")), sort_keys=True, default=str)
print(hashlib.sha256(content.encode()).hexdigest())' "$file")" ;;
        *)
            echo "$file bytes $(sha256sum "$file" | cut -d' ' -f1)" ;;
    esac
done

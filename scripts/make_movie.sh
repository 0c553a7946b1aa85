#!/usr/bin/env bash
# Frames into an H.264 movie that players show as rendered:
#   scripts/make_movie.sh FRAMES FPS OUT.mp4 [FRAME_COUNT]
# FRAMES is an ffmpeg pattern of PNGs (frame.%04d.png) encoded for an HD video display:
# patina-render's display "Rec.1886 Rec.709" (docs/colour.md). The movie is converted to
# Y'CbCr with the BT.709 matrix in limited range and tagged so (BT.709 primaries, transfer
# and matrix): without tags a player guesses, and most guess BT.601 for small frames.
# With FRAME_COUNT, a movie holding another number of frames is an error. Written under a
# temporary name and renamed: OUT.mp4 is never left half-written.
set -euo pipefail
if [[ $# -lt 3 ]]; then
  echo "usage: $0 FRAMES FPS OUT.mp4 [FRAME_COUNT]" >&2
  exit 2
fi
frames=$1 fps=$2 out=$3 expected=${4:-}
tmp="${out%.mp4}.tmp.$$.mp4"
trap 'rm -f "$tmp"' EXIT
ffmpeg -y -loglevel error -framerate "$fps" -i "$frames" \
  -vf "pad=ceil(iw/2)*2:ceil(ih/2)*2,scale=out_color_matrix=bt709:out_range=tv,format=yuv420p" \
  -c:v libx264 -color_primaries bt709 -color_trc bt709 -colorspace bt709 -color_range tv \
  "$tmp"
if [[ -n "$expected" ]]; then
  count=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames \
          -of csv=p=0 "$tmp")
  if [[ "$count" != "$expected" ]]; then
    echo "make_movie: $out would hold $count frames, not $expected" >&2
    exit 1
  fi
fi
mv "$tmp" "$out"
trap - EXIT

#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Peak memory of a big-image warp: a W×H RGB8 photo (default
# 30000×20000, 600 Mpix) warped through resources/sample.artcam into a TIFF, measured with
# /usr/bin/time -v, against the sizes of the input and output pixels. Target: input + output +
# a small constant (the warp reads and writes the stored 8-bit samples in bands of rows, no float
# copy; the input is freed before the output is encoded).
#
# usage: packaging/bench-big-image.sh [BUILD_DIR]     (env: W, H, TMPDIR)
# Needs about (W·H·7 bytes + 1 GiB) of memory and W·H·5 bytes of disk; the files are removed.
set -eu
cd "$(dirname "$0")/.."
BUILD=${1:-build}
ARTCAM="$BUILD/app/artcam"
W=${W:-30000}
H=${H:-20000}
WORK=$(mktemp -d "${TMPDIR:-/tmp}/artcam-big.XXXXXX")
trap 'rm -rf "$WORK"' EXIT INT TERM

peak_kib() { sed -n 's/^[[:space:]]*Maximum resident set size (kbytes): //p' "$1"; }

# The baseline: the same command on the 600×400 sample photo (process, libraries, OIIO).
/usr/bin/time -v "$ARTCAM" warp resources/coffee.png resources/sample.artcam -o "$WORK/small.tif" \
  --quiet >/dev/null 2>"$WORK/small.time"
# The big photo: the sample photo warped up to W×H, as an 8-bit RGB JPEG.
"$ARTCAM" warp resources/coffee.png resources/sample.artcam -o "$WORK/big.jpg" --size "${W}x${H}" \
  --quiet >/dev/null
/usr/bin/time -v "$ARTCAM" warp "$WORK/big.jpg" resources/sample.artcam -o "$WORK/big-out.tif" \
  --stats --quiet >"$WORK/big.out" 2>"$WORK/big.time"
cat "$WORK/big.out"
grep -E 'render_ms|Elapsed|User time|System time' "$WORK/big.time" || true

base=$(peak_kib "$WORK/small.time")
peak=$(peak_kib "$WORK/big.time")
# Input: RGB8. Output: RGBA8 (the warp adds alpha where the format stores it; TIFF does).
awk -v w="$W" -v h="$H" -v base="$base" -v peak="$peak" 'BEGIN {
  mib = 1024 * 1024; in_b = w * h * 3; out_b = w * h * 4
  printf "input  %dx%d RGB8   %8.1f MiB\n", w, h, in_b / mib
  printf "output %dx%d RGBA8  %8.1f MiB\n", w, h, out_b / mib
  printf "peak RSS            %8.1f MiB (baseline on the 600x400 sample: %.1f MiB)\n", peak / 1024, base / 1024
  printf "peak - (in + out)   %8.1f MiB\n", peak / 1024 - (in_b + out_b) / mib
}'

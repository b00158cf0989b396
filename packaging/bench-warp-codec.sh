#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# `artcam warp` JPEG -> JPEG, whole process, beside the codec floor: djpeg + cjpeg of the same
# files (libjpeg-turbo's own tools, the same library the warp decodes and encodes with), and
# the warp's peak memory beside input + output + 64 MiB. A benchmark: it prints figures and
# asserts nothing about time.
#
#   bash packaging/bench-warp-codec.sh [--runs N] [--quality Q] [--artcam PATH] [IN.jpg [CAM.artcam]]
#
# IN defaults to resources/coffee.png resized to 6000x4000 (24 Mpix, quality 95) with oiiotool,
# CAM to resources/sample.artcam; both encoders write quality Q (default 95). Each command runs
# N times (default 5) after one warm-up, one after the other, and the median wall time is
# printed, so compare the figures of one line: the machine's load moves all of them. Prints:
#   warp_ms= djpeg_ms= cjpeg_ms= floor_ms= ratio= peak_mib= base_mib= budget_mib= load=
# ratio is warp over djpeg + cjpeg (the target is <= 1.3); peak_mib the warp's peak resident
# memory, base_mib that of `artcam --version` (the shared libraries alone: OpenImageIO loads
# some 260), budget_mib input + output as decoded (8-bit) + 64 MiB, to compare with
# peak_mib - base_mib.
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
runs=5
quality=95
artcam="${ARTCAM_BUILD_DIR:-$here/build}/app/artcam"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --quality) quality="$2"; shift 2 ;;
    --artcam) artcam="$2"; shift 2 ;;
    -h|--help) sed -n '3,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) break ;;
  esac
done
for tool in djpeg cjpeg oiiotool /usr/bin/time; do
  command -v "$tool" >/dev/null || { echo "bench-warp-codec: $tool is missing (packaging/install-deps.sh)" >&2; exit 1; }
done
[[ -x "$artcam" ]] || { echo "bench-warp-codec: $artcam: not built (cmake --build build --target artcam)" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
input="${1:-}"
camera="${2:-$here/resources/sample.artcam}"
if [[ -z "$input" ]]; then
  input="$work/in.jpg"
  oiiotool "$here/resources/coffee.png" --resize 6000x4000 --compression jpeg:95 -o "$input"
fi

# Median wall time in ms of running "$@" $runs times (one warm-up first).
median_ms() {
  "$@" >/dev/null 2>&1
  local times=()
  for ((k = 0; k < runs; ++k)); do
    local t0 t1
    t0=$(date +%s%N)
    "$@" >/dev/null 2>&1
    t1=$(date +%s%N)
    times+=($(( (t1 - t0) / 1000000 )))
  done
  printf '%s\n' "${times[@]}" | sort -n | sed -n "$(( (runs + 1) / 2 ))p"
}

warp_ms=$(median_ms "$artcam" warp "$input" "$camera" -o "$work/out.jpg" --overwrite --quiet --quality "$quality")
djpeg_ms=$(median_ms djpeg -outfile "$work/in.ppm" "$input")
cjpeg_ms=$(median_ms cjpeg -quality "$quality" -outfile "$work/c.jpg" "$work/in.ppm")
peak_kib=$(/usr/bin/time -f '%M' "$artcam" warp "$input" "$camera" -o "$work/out.jpg" --overwrite --quiet --quality "$quality" 2>&1 >/dev/null | tail -1)
base_kib=$(/usr/bin/time -f '%M' "$artcam" --version 2>&1 >/dev/null | tail -1)

# Input and output as decoded (8-bit samples), from their headers.
pixels_bytes() { oiiotool --info -v "$1" | sed -n 's/.* \([0-9]*\) x \([0-9]*\), \([0-9]*\) channel.*/\1 \2 \3/p' | head -1 | awk '{print $1*$2*$3}'; }
in_bytes=$(pixels_bytes "$input")
out_bytes=$(pixels_bytes "$work/out.jpg")
floor_ms=$((djpeg_ms + cjpeg_ms))
awk -v w="$warp_ms" -v d="$djpeg_ms" -v c="$cjpeg_ms" -v f="$floor_ms" -v p="$peak_kib" -v b="$base_kib" \
    -v i="$in_bytes" -v o="$out_bytes" -v load="$(cut -d' ' -f1 /proc/loadavg)" 'BEGIN {
  printf "warp_ms=%d djpeg_ms=%d cjpeg_ms=%d floor_ms=%d ratio=%.2f peak_mib=%.0f base_mib=%.0f budget_mib=%.0f load=%s\n",
         w, d, c, f, w / f, p / 1024, b / 1024, (i + o) / 1048576 + 64, load }'

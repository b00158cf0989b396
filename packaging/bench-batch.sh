#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# artcam batch against the same warps one after the other: N photos of
# W×H RGB8 JPEG → RGBA8 TIFF. Prints both wall times, their ratio and the batch's peak RSS
# beside the pipeline's bound (2 inputs + 2 outputs in flight) and one warp's peak.
# usage: packaging/bench-batch.sh [BUILD_DIR]      (env: N=6, W=6000, H=4000, TMPDIR)
set -eu
cd "$(dirname "$0")/.."
ARTCAM="${1:-build}/app/artcam"
N=${N:-6}
W=${W:-6000}
H=${H:-4000}
WORK=$(mktemp -d "${TMPDIR:-/tmp}/artcam-batch.XXXXXX")
trap 'rm -rf "$WORK"' EXIT INT TERM
peak_kib() { sed -n 's/^[[:space:]]*Maximum resident set size (kbytes): //p' "$1"; }
cpu_s() { awk -F': ' '/User time|System time/ { s += $2 } END { print s }' "$1"; }
wall_s() { sed -n 's/^[[:space:]]*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$1" |
  awk -F: '{ s = 0; for (i = 1; i <= NF; i++) s = s * 60 + $i; print s }'; }

mkdir -p "$WORK/in" "$WORK/seq" "$WORK/batch"
for i in $(seq 1 "$N"); do
  "$ARTCAM" warp resources/coffee.png resources/sample.artcam -o "$WORK/in/p$i.jpg" \
    --size "${W}x${H}" --quiet >/dev/null
done
uptime
/usr/bin/time -v sh -c "for f in '$WORK'/in/*.jpg; do
  '$ARTCAM' warp \"\$f\" resources/sample.artcam -o '$WORK'/seq/\$(basename \"\$f\" .jpg).tif --quiet >/dev/null
done" 2>"$WORK/seq.time"
/usr/bin/time -v "$ARTCAM" warp "$WORK/in/p1.jpg" resources/sample.artcam -o "$WORK/one.tif" \
  --quiet >/dev/null 2>"$WORK/one.time"
/usr/bin/time -v "$ARTCAM" batch resources/sample.artcam "$WORK"/in/*.jpg -o "$WORK/batch" \
  --format tif --quiet 2>"$WORK/batch.time"
uptime
awk -v n="$N" -v w="$W" -v h="$H" -v seq="$(wall_s "$WORK/seq.time")" \
  -v bat="$(wall_s "$WORK/batch.time")" -v one="$(peak_kib "$WORK/one.time")" \
  -v peak="$(peak_kib "$WORK/batch.time")" -v seq_cpu="$(cpu_s "$WORK/seq.time")" \
  -v bat_cpu="$(cpu_s "$WORK/batch.time")" 'BEGIN {
  mib = 1024 * 1024; in_b = w * h * 3 / mib; out_b = w * h * 4 / mib
  printf "%d warps one after the other: %.1f s wall, %.1f s CPU; batch: %.1f s wall, %.1f s CPU (wall ratio %.2f)\n", n, seq, seq_cpu, bat, bat_cpu, seq / bat
  printf "peak RSS: one warp %.0f MiB, batch %.0f MiB (one input %.0f MiB, one output %.0f MiB)\n", one / 1024, peak / 1024, in_b, out_b
}'

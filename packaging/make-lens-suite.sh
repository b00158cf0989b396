#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Writes three cameras from real lenses of the lensfun database at 6000x4000, for the speed
# benchmarks: a mild compact zoom, a strong wide angle and a fisheye (converted to rectilinear).
# Each is what `artcam lens camera` makes: a single camera when one is within 0.5 px of
# lensfun's model over the frame, else a piecewise one; the error against lensfun is printed.
#
#   bash packaging/make-lens-suite.sh [OUTDIR]      (default: lens-suite/; ARTCAM=path/to/artcam)
set -euo pipefail

out="${1:-lens-suite}"
artcam="${ARTCAM:-${ARTCAM_BUILD_DIR:-build}/app/artcam}"
mkdir -p "$out"

make_camera() {  # NAME FOCAL FILE
  echo "== $1 at $2 mm -> $out/$3"
  "$artcam" lens camera --lens "$1" --focal "$2" --size 6000x4000 -o "$out/$3" --overwrite
}

make_camera "Canon PowerShot G11 & compatibles (Standard)" 15 lens-compact-g11-15mm.artcam
make_camera "Canon EF-S 10-22mm f/3.5-4.5 USM" 10 lens-wide-efs10-22-10mm.artcam
make_camera "Samyang 8mm f/3.5 Fish-Eye CS" 8 lens-fisheye-samyang8.artcam

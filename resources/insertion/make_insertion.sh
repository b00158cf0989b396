#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Remakes the environment-matting samples and the README's before/after images with
# the CLI: ray-traced photos, their calibration-grid matches, the emblem, and the insertions.
# usage: resources/insertion/make_insertion.sh path/to/artcam   (run from the repository root;
#        ImageMagick's convert joins the before/after pairs)
set -eu
artcam=${1:-build/app/artcam}
out=resources/insertion
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

for scene in mirror-sphere water-glass; do
  "$artcam" sample "$scene" --overwrite -o "$out"
  # The mirror sphere as in Fig 7(c): on the table (its homography from four table clicks,
  # outside the sphere's outline) and in the reflection.
  table=""
  [ "$scene" = mirror-sphere ] &&
    table="--table $out/$scene-table.csv --region $out/$scene-region.csv"
  # shellcheck disable=SC2086
  "$artcam" insert "$out/$scene.png" "$out/emblem.png" --matches "$out/$scene-grid.csv" \
    $table --max-error 0.25 -o "$tmp/$scene-inserted.png"
  convert "$out/$scene.png" "$tmp/$scene-inserted.png" +append "$out/$scene-before-after.png"
done

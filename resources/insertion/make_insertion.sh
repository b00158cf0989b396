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
  "$artcam" insert "$out/$scene.png" "$out/emblem.png" --matches "$out/$scene-grid.csv" \
    --max-error 0.25 -o "$tmp/$scene-inserted.png"
  convert "$out/$scene.png" "$tmp/$scene-inserted.png" +append "$out/$scene-before-after.png"
done

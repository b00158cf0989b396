#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Remakes the paper's Fig 6 sample and the README's figure with the CLI: a silver and a green
# reflector rendered in code under the same lights, their colour samples, and the silver one
# relit by an affine and by the fitted (quadratic) colour camera, next to the green truth.
# usage: resources/specular/make_specular.sh path/to/artcam   (run from the repository root;
#        ImageMagick's convert joins the panels)
set -eu
artcam=${1:-build/app/artcam}
out=resources/specular
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$artcam" sample specular-pair --size 320x320 --overwrite -o "$out"
"$artcam" fit --block colour "$out/specular-samples.csv" --size 320x320 --model affine \
  -o "$tmp/affine.artcam" >/dev/null
"$artcam" fit --block colour "$out/specular-samples.csv" --size 320x320 \
  -o "$tmp/relight.artcam" | head -2
"$artcam" warp "$out/silver.png" "$tmp/affine.artcam" -o "$tmp/affine.png"
"$artcam" warp "$out/silver.png" "$tmp/relight.artcam" -o "$tmp/relit.png"
convert "$out/silver.png" "$tmp/affine.png" "$tmp/relit.png" "$out/green.png" +append \
  "$out/specular-relight.png"

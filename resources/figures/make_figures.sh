#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# The paper's Figs 1–8, each as one picture (resources/figures/figN.png), made from the bundled
# samples and images made in code, with the CLI alone (oiiotool lays the panels side by side).
# usage: resources/figures/make_figures.sh path/to/artcam   (run from the repository root)
set -eu
artcam=${1:-build/app/artcam}
out=resources/figures
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
row() {  # row OUT PANEL... : the panels side by side, each 256 px tall, 4 px of white between
  dest=$1
  shift
  convert "$@" -resize x256 -bordercolor white -border 2x0 +append -alpha off "$dest"
}

# Fig 1: the cube of cubes through 3D cameras (original, twist, pin-cushion, colour scale,
# chromatic aberration).
"$artcam" preset cube-of-cubes -o "$tmp/cube.ply" >/dev/null
for panel in identity twist-3d pincushion-3d colour-scale chromatic-aberration-3d; do
  "$artcam" preset "$panel" -o "$tmp/$panel.artcam" >/dev/null
  layers=""
  [ "$panel" = chromatic-aberration-3d ] && layers="--layers rgb"
  # shellcheck disable=SC2086
  "$artcam" render "$tmp/cube.ply" "$tmp/$panel.artcam" $layers --size 256x256 -o "$tmp/f1-$panel.png" >/dev/null
done
row "$out/fig1.png" "$tmp/f1-identity.png" "$tmp/f1-twist-3d.png" "$tmp/f1-pincushion-3d.png" \
  "$tmp/f1-colour-scale.png" "$tmp/f1-chromatic-aberration-3d.png"

# Fig 2: a stereo pair, its depth, and the walls unfolded (each seen orthogonally, the roof
# stretched over the shorter one), in pencil.
"$artcam" sample stereo-house -o "$tmp/house" >/dev/null
"$artcam" stereo "$tmp/house/house-left.png" "$tmp/house/house-right.png" --baseline-focal 140 \
  -o "$tmp/house/depth.exr" >/dev/null
"$artcam" unfold "$tmp/house/house-left.png" --depth "$tmp/house/depth.exr" \
  --walls "$tmp/house/house-walls.csv" --focal 560 -o "$tmp/unfold.artcam" >/dev/null
"$artcam" warp "$tmp/house/house-left.png" "$tmp/unfold.artcam" -o "$tmp/unfolded.png" \
  --edge black --finish pencil >/dev/null
# The depth map shown as grey, darker nearer (depth / 40; black where nothing matched).
oiiotool "$tmp/house/depth.exr" --ch 0,0,0 --mulc 0.025 -d uint8 -o "$tmp/depth-grey.png"
row "$out/fig2.png" "$tmp/house/house-left.png" "$tmp/house/house-right.png" "$tmp/depth-grey.png" \
  "$tmp/unfolded.png"

# Fig 3: depth planes drive aerial perspective and depth of field (the bundled project).
"$artcam" export resources/depth-effects.artcamproj -o "$tmp/f3.png" >/dev/null
row "$out/fig3.png" resources/coffee.png "$tmp/f3.png"

# Fig 4: chromatic aberration, three layers (R, G, B) of one camera.
"$artcam" preset chromatic-aberration --red 0.02 --blue -0.02 -o "$tmp/ca.artcam" >/dev/null
"$artcam" warp resources/coffee.png "$tmp/ca.artcam" -o "$tmp/f4.png" >/dev/null
row "$out/fig4.png" resources/coffee.png "$tmp/f4.png"

# Fig 5: a grid of nine points, the centre pulled; the fitted warp rendered in pencil.
printf 'src_x,src_y,dst_x,dst_y\n50,50,50,50\n300,50,300,50\n550,50,550,50\n50,200,50,200\n300,200,340,170\n550,200,550,200\n50,350,50,350\n300,350,300,350\n550,350,550,350\n' >"$tmp/nine.csv"
"$artcam" fit "$tmp/nine.csv" --size 600x400 -o "$tmp/nine.artcam" >/dev/null
"$artcam" warp resources/coffee.png "$tmp/nine.artcam" -o "$tmp/f5.png" --finish pencil >/dev/null
row "$out/fig5.png" resources/coffee.png "$tmp/f5.png"

# Fig 6: a silver reflector relit as the green one by a fitted colour map.
"$artcam" fit --block colour resources/specular/specular-samples.csv --size 320x320 \
  -o "$tmp/relight.artcam" >/dev/null
"$artcam" warp resources/specular/silver.png "$tmp/relight.artcam" -o "$tmp/relit.png" >/dev/null
row "$out/fig6.png" resources/specular/silver.png "$tmp/relit.png" resources/specular/green.png

# Figs 7 and 8: a graphic inserted into a reflection (on the table too) and refractions.
"$artcam" insert resources/insertion/mirror-sphere.png resources/insertion/emblem.png \
  --matches resources/insertion/mirror-sphere-grid.csv --table resources/insertion/mirror-sphere-table.csv \
  --region resources/insertion/mirror-sphere-region.csv --max-error 0.25 -o "$tmp/f7.png" >/dev/null
row "$out/fig7.png" resources/insertion/mirror-sphere.png "$tmp/f7.png"
"$artcam" insert resources/insertion/water-glass.png resources/insertion/emblem.png \
  --matches resources/insertion/water-glass-grid.csv --max-error 0.25 -o "$tmp/f8.png" >/dev/null
# Fig 8 whole: a glass filled to half its height, the graphic through the water and then
# through the air above it (each region its own piecewise camera).
"$artcam" sample glass-of-water -o "$tmp/glass" >/dev/null
"$artcam" insert "$tmp/glass/glass-of-water.png" "$tmp/glass/emblem.png" \
  --matches "$tmp/glass/glass-of-water-grid.csv" --max-error 0.25 -o "$tmp/f8-water.png" >/dev/null
"$artcam" insert "$tmp/f8-water.png" "$tmp/glass/emblem.png" \
  --matches "$tmp/glass/glass-of-water-air-grid.csv" --max-error 0.25 -o "$tmp/f8-both.png" >/dev/null
row "$out/fig8.png" resources/insertion/water-glass.png "$tmp/f8.png" \
  "$tmp/glass/glass-of-water.png" "$tmp/f8-both.png"
echo "wrote $out/fig1.png … $out/fig8.png"

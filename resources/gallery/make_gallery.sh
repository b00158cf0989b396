#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Renders the paper's Fig 1 panels (and the view cameras) from resources/cube.ply with the CLI.
# usage: resources/gallery/make_gallery.sh path/to/artcam   (run from the repository root)
set -eu
artcam=${1:-build/app/artcam}
out=resources/gallery
cloud=resources/cube.ply
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$artcam" preset cube-of-cubes -o "$tmp/cube.ply" >/dev/null
cmp -s "$tmp/cube.ply" "$cloud" || echo "note: $cloud differs from what the code makes now" >&2

# Fig 1: original, twist, pin-cushion / inverse perspective, colour scale, chromatic aberration.
# The point-cloud presets end in -3d (the plain names are the image effects); the files keep the
# panel names.
for panel in identity twist pincushion inverse-perspective colour-scale chromatic-aberration; do
  case $panel in
    identity | colour-scale) preset=$panel ;;
    *) preset=$panel-3d ;;
  esac
  "$artcam" preset "$preset" -o "$tmp/$panel.artcam" >/dev/null
done
"$artcam" render "$cloud" "$tmp/identity.artcam" --size 256x256 --overwrite -o "$out/original.png"
"$artcam" render "$cloud" "$tmp/twist.artcam" --size 256x256 --overwrite -o "$out/twist.png"
"$artcam" render "$cloud" "$tmp/pincushion.artcam" --size 256x256 --overwrite -o "$out/pincushion.png"
"$artcam" render "$cloud" "$tmp/inverse-perspective.artcam" --size 256x256 --overwrite -o "$out/inverse-perspective.png"
"$artcam" render "$cloud" "$tmp/colour-scale.artcam" --size 256x256 --overwrite -o "$out/colour-scale.png"
"$artcam" render "$cloud" "$tmp/chromatic-aberration.artcam" --layers rgb --size 256x256 \
  --overwrite -o "$out/chromatic-aberration.png"

# The family of view cameras on the unmoved cube.
for view in orthographic pushbroom xslit glc rational-lens; do
  "$artcam" preset "$view" -o "$tmp/$view.artcam" >/dev/null
  "$artcam" render "$cloud" "$tmp/identity.artcam" --view "$tmp/$view.artcam" --size 256x256 \
    --overwrite -o "$out/view-$view.png"
done

#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Renders the image effects on the bundled photo with the CLI (artcam preset + artcam warp).
# usage: resources/gallery/effects/make_effects_gallery.sh path/to/artcam   (from the repo root)
# The depth of coffee.png is a stand-in made here with oiiotool: the table seen from above, a
# plane in inverse depth, 1/d from 1/20 at the top row to 1 at the bottom row (depth 20 … 1).
set -eu
artcam=${1:-build/app/artcam}
photo=resources/coffee.png
out=resources/gallery/effects
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
size=300x200

oiiotool --pattern fill:top=0.05:bottom=1.0 600x400 1 --powc -1 -d float -o "$tmp/depth.exr"

# The original at the gallery's size: a radial lens with k = 0 is the identity.
"$artcam" preset barrel --k 0 -o "$tmp/identity.artcam" >/dev/null
"$artcam" warp "$photo" "$tmp/identity.artcam" --size $size --overwrite -o "$out/original.png" >/dev/null
"$artcam" preset barrel --k -0.25 -o "$tmp/barrel.artcam" >/dev/null
"$artcam" preset pincushion --k 0.25 -o "$tmp/pincushion.artcam" >/dev/null
"$artcam" preset twist --rate 0.4 -o "$tmp/twist.artcam" >/dev/null
"$artcam" preset inverse-perspective --gain 0.5 -o "$tmp/inverse-perspective.artcam" >/dev/null
"$artcam" preset chromatic-aberration --red 0.015 --blue -0.015 -o "$tmp/chromatic-aberration.artcam" >/dev/null
"$artcam" preset colour-shift --s-red 0.12 --s-green 0 --s-blue -0.08 -o "$tmp/colour-shift.artcam" >/dev/null
"$artcam" preset aerial-perspective --near 1 --far 20 --strength 0.85 -o "$tmp/aerial-perspective.artcam" >/dev/null
"$artcam" preset depth-of-field --focus 1.9 --blur 0.03 -o "$tmp/depth-of-field.artcam" >/dev/null
for effect in barrel pincushion twist inverse-perspective chromatic-aberration colour-shift \
              aerial-perspective depth-of-field; do
  "$artcam" warp "$photo" "$tmp/$effect.artcam" --depth "$tmp/depth.exr" --size $size \
    --overwrite -o "$out/$effect.png"
done

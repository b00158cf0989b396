#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Renders the hicolor PNG sizes of the studio's icon from its hand-written SVG (rsvg-convert,
# Debian package librsvg2-bin). The PNGs are committed so a build needs no SVG renderer; run this
# after editing packaging/desktop/icons/org.artcam.Studio.svg.
set -euo pipefail
dir="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/desktop/icons"
for size in 16 24 32 48 64 128 256; do
  rsvg-convert -w "$size" -h "$size" "$dir/org.artcam.Studio.svg" -o "$dir/org.artcam.Studio-$size.png"
done
echo "render-icons: wrote $(ls "$dir"/*.png | wc -l) PNGs in $dir"

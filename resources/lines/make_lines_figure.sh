#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# The README's straight-line calibration picture, from code-made images: a façade photographed
# through a barrel lens (make_lines_figure.py), seven traced edges, `artcam fit --lines`, then
# `artcam warp`; left the photo with the traced points (red) and the chords through their ends
# (yellow), right the straightened photo with the same points mapped by `artcam map`, and two
# held-out edges (cyan) the fit never saw.
# usage: resources/lines/make_lines_figure.sh [path/to/artcam]   (from the repo root; needs
# python3 and oiiotool)
set -eu
artcam=${1:-build/app/artcam}
here=resources/lines
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

python3 "$here/make_lines_figure.py" scene "$tmp"
oiiotool "$tmp/photo.ppm" -o "$tmp/photo.png"
"$artcam" fit --lines "$tmp/lines.csv" -o "$tmp/lens.artcam" --size 1200x800 -q \
  | grep -v "^wrote " > "$here/fit-report.txt"
"$artcam" warp "$tmp/photo.png" "$tmp/lens.artcam" -o "$tmp/straight.png" -q >/dev/null
oiiotool "$tmp/straight.png" --ch R,G,B -o "$tmp/straight.ppm"

# The traced points through the camera: labels kept, positions from artcam map's X,Y.
for set in lines held-out; do
  { echo "x,y"; tail -n +2 "$tmp/$set.csv" | cut -d, -f2,3; } > "$tmp/$set-xy.csv"
  "$artcam" map "$tmp/lens.artcam" "$tmp/$set-xy.csv" | cut -d, -f3,4 > "$tmp/$set-mapped-xy.csv"
  { echo "line,x,y"; tail -n +2 "$tmp/$set.csv" | cut -d, -f1 | paste -d, - "$tmp/$set-mapped-xy.csv"; } \
    > "$tmp/$set-mapped.csv"
done
python3 "$here/make_lines_figure.py" overlay "$tmp/photo.ppm" "$tmp/lines.csv" "$tmp/before.ppm"
python3 "$here/make_lines_figure.py" overlay "$tmp/straight.ppm" "$tmp/lines-mapped.csv" "$tmp/after1.ppm"
python3 "$here/make_lines_figure.py" overlay "$tmp/after1.ppm" "$tmp/held-out-mapped.csv" "$tmp/after.ppm" held
oiiotool "$tmp/before.ppm" "$tmp/after.ppm" --mosaic:pad=16 2x1 --resize 1216x400 -o "$here/straight-lines.png"
echo "wrote $here/straight-lines.png and $here/fit-report.txt"

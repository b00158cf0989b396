#!/usr/bin/env bash
# Takes the README's screenshot: the real main window on the bundled sample project, under Xvfb
# (Debian packages xvfb and imagemagick). Usage: bash packaging/screenshot.sh [OUT.png]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/resources/screenshots/studio-main-window.png}"
display=":77"
Xvfb "$display" -screen 0 1600x1000x24 >/dev/null 2>&1 &
xvfb=$!
trap 'kill $xvfb $studio 2>/dev/null || true' EXIT
sleep 2
DISPLAY="$display" "$root/build/app/artcam-studio" "$root/resources/sample.artcamproj" &
studio=$!
sleep 10
DISPLAY="$display" import -window root "$out.full.png"
convert "$out.full.png" -crop 1400x900+0+0 +repage -resize 1100x -strip "$out"
rm -f "$out.full.png"
echo "screenshot: $out"

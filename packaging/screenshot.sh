#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Takes the README's screenshot: the real main window on the bundled sample project, under Xvfb
# (Debian packages xvfb and imagemagick). Usage: bash packaging/screenshot.sh [OUT.png] [PROJECT]
# (STUDIO names the binary, SETTLE the seconds the window gets before the shot, BEFORE_SHOT a
# bash command run against the window just before it, e.g. xdotool keys; other screenshot
# scripts prepare a project and call this one).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/resources/screenshots/studio-main-window.png}"
project="${2:-$root/resources/sample.artcamproj}"
studio_bin="${STUDIO:-$root/build/app/artcam-studio}"
display="${DISPLAY_NUMBER:-:77}"
Xvfb "$display" -screen 0 1600x1000x24 >/dev/null 2>&1 &
xvfb=$!
studio=""
trap 'kill $xvfb $studio 2>/dev/null || true' EXIT
sleep 2
DISPLAY="$display" "$studio_bin" "$project" &
studio=$!
sleep "${SETTLE:-10}"
if [[ -n "${BEFORE_SHOT:-}" ]]; then
  DISPLAY="$display" bash -c "$BEFORE_SHOT"
  sleep "${BEFORE_SHOT_SETTLE:-3}"
fi
DISPLAY="$display" import -window root "$out.full.png"
convert "$out.full.png" -crop 1400x900+0+0 +repage -resize 1100x -strip "$out"
rm -f "$out.full.png"
echo "screenshot: $out"

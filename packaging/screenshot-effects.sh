#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Takes the README's depth-effects screenshot under Xvfb (Debian packages xvfb, xdotool and
# imagemagick): the bundled resources/depth-effects.artcamproj (two painted depth planes, aerial
# perspective then depth of field) in the canvas's Split view (Alt+3) - the photo under its depth
# overlay left of the divider, the result right - with the Effects dock raised.
# Usage: bash packaging/screenshot-effects.sh [OUT.png]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/resources/screenshots/studio-depth-effects.png}"
# A throw-away settings home: no recent files or dock layout of the user's sessions.
home="$(mktemp -d)"
trap 'rm -rf "$home"' EXIT
# No shortcut raises a dock, so the Effects tab is clicked where it sits along the docks' bottom
# edge in the 1400x900 window; the mouse is then parked off the window (no hover highlight).
before='w="$(xdotool search --onlyvisible --name "ARTcam Studio$" | head -n 1)"
xdotool windowfocus --sync "$w" key alt+3
xdotool mousemove 1128 863 click 1 mousemove 1590 990'
XDG_CONFIG_HOME="$home/config" XDG_DATA_HOME="$home/data" STUDIO="${STUDIO:-}" \
  DISPLAY_NUMBER="${DISPLAY_NUMBER:-:78}" BEFORE_SHOT="$before" \
  bash "$root/packaging/screenshot.sh" "$out" "$root/resources/depth-effects.artcamproj"

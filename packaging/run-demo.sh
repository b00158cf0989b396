#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Command (a) of the README: install dependencies, build what the demo runs (the artcam CLI, and
# the studio when a display is there to show it), and run the main job on the bundled sample:
# warp resources/coffee.png through resources/sample.artcam. The tests are built by command (b),
# packaging/build-and-test.sh, in the same build/ tree.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ARTCAM_BUILD_DIR:-$root/build}"
start=$(date +%s)
bash "$root/packaging/install-deps.sh"
targets="artcam"
display="${DISPLAY:-}${WAYLAND_DISPLAY:-}"
[[ -n "$display" ]] && targets+=" artcam-studio"
ARTCAM_BUILD_TARGETS="$targets" bash "$root/packaging/build.sh"
out="$root/out"
mkdir -p "$out"
"$build/app/artcam" info "$root/resources/sample.artcam"
"$build/app/artcam" warp "$root/resources/coffee.png" "$root/resources/sample.artcam" \
  -o "$out/coffee-warped.png" --stats --overwrite
echo "demo: the warped sample is $out/coffee-warped.png ($(($(date +%s) - start)) s from the start)"
if [[ -n "$display" && -x "$build/app/artcam-studio" ]]; then
  exec "$build/app/artcam-studio" "$root/resources/sample.artcamproj"
fi

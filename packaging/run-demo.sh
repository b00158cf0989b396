#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Command (a) of the README: install dependencies, build, and run the main job on the bundled
# sample: warp resources/coffee.png through resources/sample.artcam with the CLI (and open the
# studio on the sample when a display is available and the studio is built).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ARTCAM_BUILD_DIR:-$root/build}"
bash "$root/packaging/install-deps.sh"
bash "$root/packaging/build.sh"
out="$root/out"
mkdir -p "$out"
"$build/app/artcam" info "$root/resources/sample.artcam"
"$build/app/artcam" warp "$root/resources/coffee.png" "$root/resources/sample.artcam" \
  -o "$out/coffee-warped.png" --stats --overwrite
echo "demo: the warped sample is $out/coffee-warped.png"
if [[ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" && -x "$build/app/artcam-studio" ]]; then
  exec "$build/app/artcam-studio" "$root/resources/sample.artcamproj"
fi

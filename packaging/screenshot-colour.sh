#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Takes the README's Colour dock screenshot under Xvfb (Debian packages xvfb and imagemagick):
# the bundled coffee photo, a reference made from it by the CLI through a warm linear colour
# map (artcam fit --block colour on samples of a known 3×3 matrix, then artcam warp: the
# colour-only path), and a project whose colour part holds ten patch pairs and that fitted
# block, so the studio opens on the Colour dock. Usage: bash packaging/screenshot-colour.sh [OUT.png] [BUILD_DIR]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/resources/screenshots/studio-colour-dock.png}"
artcam="${ARTCAM:-$root/build/app/artcam}"
studio_bin="${STUDIO:-$root/build/app/artcam-studio}"
work="$(mktemp -d)"
display=":79"
python3 - "$work" <<'PY'
import random, sys
work = sys.argv[1]
m = [[1.12, 0.06, 0.0], [0.03, 0.93, 0.02], [0.0, 0.06, 0.72]]  # warm: more red, less blue
random.seed(3)
rows = ["src_r,src_g,src_b,dst_r,dst_g,dst_b"]
for _ in range(14):
    c = [random.uniform(0.02, 0.8) for _ in range(3)]
    d = [sum(m[r][k] * c[k] for k in range(3)) for r in range(3)]
    rows.append(",".join("%.17g" % v for v in c + d))
open(work + "/warm.csv", "w").write("\n".join(rows) + "\n")
PY
"$artcam" fit --block colour "$work/warm.csv" -o "$work/warm.artcam" --size 600x400 --model linear
"$artcam" warp "$root/resources/coffee.png" "$work/warm.artcam" -o "$work/coffee-warm.png"
python3 - "$root" "$work" <<'PY'
import json, sys
root, work = sys.argv[1], sys.argv[2]
p = json.load(open(root + "/resources/sample.artcamproj"))
p["photo"] = root + "/resources/coffee.png"
p["version"] = 2
points = [(290, 140), (200, 80), (120, 250), (540, 120), (40, 40), (470, 330), (300, 330),
          (360, 285), (230, 270), (520, 240)]
p["parts"] = {"colour": {
    "radius": 6, "reference": work + "/coffee-warm.png",
    "samples": [{"source": [x + 0.5, y + 0.5], "reference": [x + 0.5, y + 0.5], "enabled": True}
                for x, y in points],
    "colour_block": json.load(open(work + "/warm.artcam"))}}
json.dump(p, open(work + "/colour.artcamproj", "w"))
PY
trap 'rm -rf "$work"' EXIT
STUDIO="$studio_bin" SETTLE=12 DISPLAY_NUMBER="$display" \
  bash "$root/packaging/screenshot.sh" "$out" "$work/colour.artcamproj"

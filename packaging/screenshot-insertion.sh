#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Takes the README's Insertion-mode screenshot under Xvfb (Debian packages xvfb, xdotool and
# imagemagick): the bundled mirror-sphere sample with its grid matches, four board corners
# clicked on the table (the exact pinhole projections of grid corners (2,2), (22,2), (22,13),
# (2,13), as a user would click them), the sphere's outline and the emblem, so the preview
# shows the paper's Fig 7(c). Usage: bash packaging/screenshot-insertion.sh [OUT.png] [BUILD_DIR]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/resources/screenshots/studio-insertion.png}"
build="${2:-$root/build}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
python3 - "$root" "$work" <<'PY'
import csv, json, math, sys
root, work = sys.argv[1], sys.argv[2]
ins = root + "/resources/insertion/"
W, H = 640, 480                       # `artcam sample mirror-sphere`'s scene at its default size
f, eye, at = 0.9 * W, (0.0, 2.2, 5.5), (0.0, 0.9, 0.0)
sub = lambda a, b: tuple(x - y for x, y in zip(a, b))
dot = lambda a, b: sum(x * y for x, y in zip(a, b))
unit = lambda a: tuple(x / math.sqrt(dot(a, a)) for x in a)
cross = lambda a, b: (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
fw = unit(sub(at, eye)); right = unit(cross(fw, (0, 1, 0))); up = cross(right, fw)
def photo(g):  # board pixel → floor point → pinhole projection (photo pixels)
    v = sub((g[0] / 512 * 4 - 2, 0.0, g[1] / 512 * 4 - 2 + 1.6), eye)
    return [0.5 * W + f * dot(v, right) / dot(v, fw), 0.5 * H - f * dot(v, up) / dot(v, fw)]
rows = list(csv.reader(open(ins + "mirror-sphere-grid.csv")))[1:]
matches = [{"board": [float(r[0]), float(r[1])], "photo": [float(r[2]), float(r[3])]} for r in rows]
for i, j in [(2, 2), (22, 2), (22, 13), (2, 13)]:
    g = [i * 512 / 24, j * 512 / 24]
    matches.append({"board": g, "photo": photo(g), "on_table": True})
region = [[float(r[0]), float(r[1])] for r in list(csv.reader(open(ins + "mirror-sphere-region.csv")))[1:]]
p = json.load(open(root + "/resources/sample.artcamproj"))
p.update({"version": 2, "photo": ins + "mirror-sphere.png", "pairs": []})
p["parts"] = {"insertion": {"board": [512, 512], "squares": 24, "max_error_px": 0.3,
                            "matches": matches, "region": region, "graphic": ins + "emblem.png",
                            "placement": {"origin": [0, 0], "width": 0}}}
json.dump(p, open(work + "/insertion.artcamproj", "w"))
PY
# The Insertion tab of the dock, then the Grid Tool (window coordinates of the 1600×1000 screen).
STUDIO="$build/app/artcam-studio" SETTLE=12 DISPLAY_NUMBER=":82" \
  BEFORE_SHOT='xdotool mousemove 1261 863 click 1; sleep 1; xdotool mousemove 953 33 click 1' \
  bash "$root/packaging/screenshot.sh" "$out" "$work/insertion.artcamproj"

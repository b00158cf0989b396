#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
# Writes resources/depth-effects.artcamproj: coffee.png with two painted depth planes (the
# table, receding from 0.6 at the bottom to 2.5 at the top; the cup and saucer, an ellipse at
# 0.8) and an effect stack of aerial perspective then depth of field focused on the cup.
# Masks use the project file's run-length bytes (core/depth/region_mask.h) in base64.
import base64, json, os

W, H = 600, 400

def runs(cov):
    out = bytearray()
    i = 0
    while i < len(cov):
        j = i + 1
        while j < len(cov) and cov[j] == cov[i]:
            j += 1
        out.append(cov[i])
        run = j - i
        while True:
            b = run & 0x7F
            run >>= 7
            out.append(b | (0x80 if run else 0))
            if not run:
                break
        i = j
    return base64.b64encode(bytes(out)).decode()

table = [255] * (W * H)
cup = [0] * (W * H)
# The saucer and the cup: two ellipses fitted by eye to coffee.png.
for cx, cy, rx, ry in ((278.0, 232.0, 202.0, 158.0), (290.0, 140.0, 120.0, 124.0)):
    for y in range(H):
        for x in range(W):
            u, v = (x + 0.5 - cx) / rx, (y + 0.5 - cy) / ry
            if u * u + v * v <= 1.0:
                cup[y * W + x] = 255

project = {
    "format": "artcam-studio-project",
    "version": 3,
    "photo": "coffee.png",
    "model": "auto",
    "pairs": [],
    "effects": [
        {"effect": "aerial-perspective",
         "params": {"haze": [0.62, 0.72, 0.86], "strength": [0.75], "near": [0.6], "far": [3.0]}},
        {"effect": "depth-of-field",
         "params": {"focus": [0.8], "blur": [0.02], "thin-lens": [1.0]}},
    ],
    "view": {"scale": 0, "centre": [300, 200], "preview_mode": 0, "opacity": 0.5},
    "depth": {"layers": [
        {"name": "Table", "size": [W, H], "mask": runs(table),
         "anchors": [{"pixel": [20.5, 390.5], "depth": 0.6}, {"pixel": [580.5, 390.5], "depth": 0.6},
                     {"pixel": [300.5, 5.5], "depth": 2.5}]},
        {"name": "Cup and saucer", "size": [W, H], "mask": runs(cup),
         "anchors": [{"pixel": [180.5, 120.5], "depth": 0.8}, {"pixel": [380.5, 120.5], "depth": 0.8},
                     {"pixel": [280.5, 330.5], "depth": 0.8}]},
    ]},
}
here = os.path.dirname(os.path.abspath(__file__))
with open(os.path.join(here, "depth-effects.artcamproj"), "w") as f:
    json.dump(project, f, indent=2)
    f.write("\n")

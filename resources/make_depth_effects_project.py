#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
# Writes resources/depth-effects.artcamproj: coffee.png with two painted depth planes (the
# table, receding from 0.6 at the bottom to 2.5 at the top; the cup and saucer, two ellipses at
# 0.8) and an effect stack of aerial perspective then depth of field focused on the cup.
# Masks use the project file's run-length bytes (core/depth/region_mask.h) in base64.
#
# --scale S --photo P --out F make the same project for a copy of coffee.png scaled by S (the
# benchmark's 24-megapixel photo: oiiotool coffee.png --resize 6000x4000 -o big.jpg, then
# --scale 10 --photo big.jpg --out big.artcamproj).
import argparse, base64, json, math, os

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("--scale", type=float, default=1.0)
ap.add_argument("--photo", default="coffee.png")
ap.add_argument("--out", default=os.path.join(here, "depth-effects.artcamproj"))
args = ap.parse_args()
S = args.scale
W, H = int(round(600 * S)), int(round(400 * S))


def encode(runs):
    """runs: [(value, length)] -> base64 of value byte + little-endian base-128 length."""
    out = bytearray()
    for value, run in runs:
        out.append(value)
        while True:
            b = run & 0x7F
            run >>= 7
            out.append(b | (0x80 if run else 0))
            if not run:
                break
    return base64.b64encode(bytes(out)).decode()


def mask_runs(inside_row):
    """inside_row(y) -> sorted disjoint [x0, x1) spans of covered pixels; merged runs."""
    runs = []
    def push(value, n):
        if n <= 0:
            return
        if runs and runs[-1][0] == value:
            runs[-1] = (value, runs[-1][1] + n)
        else:
            runs.append((value, n))
    for y in range(H):
        x = 0
        for x0, x1 in inside_row(y):
            push(0, x0 - x)
            push(255, x1 - x0)
            x = x1
        push(0, W - x)
    return runs


# The saucer and the cup: two ellipses fitted by eye to coffee.png (its 600x400 pixels).
ellipses = [(278.0, 232.0, 202.0, 158.0), (290.0, 140.0, 120.0, 124.0)]


def cup_row(y):
    spans = []
    for cx, cy, rx, ry in ellipses:
        cx, cy, rx, ry = cx * S, cy * S, rx * S, ry * S
        v = (y + 0.5 - cy) / ry
        if abs(v) > 1.0:
            continue
        half = rx * math.sqrt(1.0 - v * v)
        # Pixel centres x + 0.5 inside [cx - half, cx + half].
        x0 = max(0, math.ceil(cx - half - 0.5))
        x1 = min(W, math.floor(cx + half - 0.5) + 1)
        if x1 > x0:
            spans.append((x0, x1))
    spans.sort()
    merged = []
    for a, b in spans:
        if merged and a <= merged[-1][1]:
            merged[-1] = (merged[-1][0], max(merged[-1][1], b))
        else:
            merged.append((a, b))
    return merged


def p(x, y):
    return [x * S + 0.5, y * S + 0.5]


project = {
    "format": "artcam-studio-project",
    "version": 3,
    "photo": args.photo,
    "model": "auto",
    "pairs": [],
    "effects": [
        {"effect": "aerial-perspective",
         "params": {"haze": [0.62, 0.72, 0.86], "strength": [0.75], "near": [0.6], "far": [3.0]}},
        {"effect": "depth-of-field",
         "params": {"focus": [0.8], "blur": [0.02], "thin-lens": [1.0]}},
    ],
    "view": {"scale": 0, "centre": [W / 2, H / 2], "preview_mode": 0, "opacity": 0.5},
    "depth": {"layers": [
        {"name": "Table", "size": [W, H], "mask": encode([(255, W * H)]),
         "anchors": [{"pixel": p(20, 390), "depth": 0.6}, {"pixel": p(580, 390), "depth": 0.6},
                     {"pixel": p(300, 5), "depth": 2.5}]},
        {"name": "Cup and saucer", "size": [W, H], "mask": encode(mask_runs(cup_row)),
         "anchors": [{"pixel": p(180, 120), "depth": 0.8}, {"pixel": p(380, 120), "depth": 0.8},
                     {"pixel": p(280, 330), "depth": 0.8}]},
    ]},
}
with open(args.out, "w") as f:
    json.dump(project, f, indent=2)
    f.write("\n")

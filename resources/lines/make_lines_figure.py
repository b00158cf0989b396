#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Pictures for the README's straight-line calibration, made from code (standard library only).

  make_lines_figure.py scene  OUT_DIR   a façade photographed through a barrel lens (photo.ppm)
                                        and the edges a user would trace on it (lines.csv)
  make_lines_figure.py overlay IMAGE.ppm POINTS.csv OUT.ppm [held]   draws each line's points
                                        (red; cyan for held-out lines) and the straight chord
                                        through its ends (yellow): the gap is the bow

The lens is the one a single quadratic camera holds exactly: the scene point of photo point u
is U = u / (1 - k |u|^2) in the normalised frame (u_n = (u - w/2) / s, s = max(w, h) / 2), so the
photo samples the scene at U, and a traced edge's points are the scene edge's points taken back
through the closed-form inverse. make_lines_figure.sh runs artcam on them.
"""
import math
import random
import sys

W, H = 1200, 800
K = 0.12
S = max(W, H) / 2.0


def normalized(x, y):
    return (x - W / 2.0) / S, (y - H / 2.0) / S


def pixel(u, v):
    return u * S + W / 2.0, v * S + H / 2.0


def scene_from_photo(x, y):
    u, v = normalized(x, y)
    d = 1.0 - K * (u * u + v * v)
    return pixel(u / d, v / d)


def photo_from_scene(x, y):
    u, v = normalized(x, y)
    rho2 = u * u + v * v
    f = 2.0 / (1.0 + math.sqrt(1.0 + 4.0 * K * rho2))
    return pixel(u * f, v * f)


# The façade, in scene pixels: wall, a grid of windows, floor bands, a roof line and a door.
WINDOW_COLS = [(90 + 150 * i, 90 + 150 * i + 80) for i in range(7)]
WINDOW_ROWS = [(150, 260), (340, 450), (530, 640)]
BANDS = [(300, 316), (490, 506), (680, 696)]


def scene_colour(x, y):
    if y < 100:
        return (150, 190, 225)  # sky
    if 100 <= y < 118:
        return (90, 60, 50)  # cornice
    for top, bottom in BANDS:
        if top <= y < bottom:
            return (200, 190, 170)
    for left, right in WINDOW_COLS:
        if left <= x < right:
            for top, bottom in WINDOW_ROWS:
                if top <= y < bottom:
                    inner = left + 6 <= x < right - 6 and top + 6 <= y < bottom - 6
                    mullion = abs(x - (left + right) / 2.0) < 3
                    return (235, 235, 230) if not inner or mullion else (60, 80, 105)
    if y >= 720:
        return (110, 110, 115)  # pavement
    return (176, 112, 84)  # brick


def write_ppm(path, pixels, w, h):
    with open(path, "wb") as f:
        f.write(b"P6\n%d %d\n255\n" % (w, h))
        f.write(bytes(pixels))


def read_ppm(path):
    data = open(path, "rb").read()
    fields = []
    pos = 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos) + 1
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    assert fields[0] == b"P6" and fields[3] == b"255", path + ": expected an 8-bit P6 PPM"
    w, h = int(fields[1]), int(fields[2])
    return bytearray(data[pos + 1:pos + 1 + 3 * w * h]), w, h


def make_scene(out_dir):
    pixels = bytearray(3 * W * H)
    offsets = [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)]
    for y in range(H):
        for x in range(W):
            r = g = b = 0
            for dx, dy in offsets:
                sx, sy = scene_from_photo(x + dx, y + dy)
                c = scene_colour(sx, sy)
                r += c[0]
                g += c[1]
                b += c[2]
            i = 3 * (y * W + x)
            pixels[i:i + 3] = bytes((r // 4, g // 4, b // 4))
    write_ppm(out_dir + "/photo.ppm", pixels, W, H)

    # Edges a user would trace: the cornice, two bands, window edges, both wall ends; clicks
    # carry 0.3 px of noise. The held-out edges (a band and a window column) are written apart.
    rng = random.Random(3)
    edges = [("cornice", (30, 118), (1170, 118), 24), ("band1", (30, 300), (1170, 300), 24),
             ("band3", (30, 696), (1170, 696), 24), ("col1", (90, 150), (90, 640), 14),
             ("col7", (1070, 150), (1070, 640), 14), ("col4r", (620, 150), (620, 640), 14),
             ("row1", (90, 260), (1070, 260), 20)]
    held = [("band2", (30, 490), (1170, 490), 24), ("col2", (240, 150), (240, 640), 14)]
    for name, rows in (("lines.csv", edges), ("held-out.csv", held)):
        with open(out_dir + "/" + name, "w") as f:
            f.write("line,x,y\n")
            for label, a, b, n in rows:
                for k in range(n):
                    t = k / (n - 1.0)
                    x, y = photo_from_scene(a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t)
                    noise = 0.3 if name == "lines.csv" else 0.0
                    f.write("%s,%.3f,%.3f\n" % (label, x + rng.gauss(0, noise), y + rng.gauss(0, noise)))


def overlay(image, points_csv, out, held=False):
    pixels, w, h = read_ppm(image)
    lines = {}
    order = []
    for row in open(points_csv).read().splitlines()[1:]:
        label, x, y = row.split(",")[:3]
        if label not in lines:
            lines[label] = []
            order.append(label)
        lines[label].append((float(x), float(y)))

    def dot(x, y, colour, radius):
        for yy in range(int(y - radius), int(y + radius) + 1):
            for xx in range(int(x - radius), int(x + radius) + 1):
                if 0 <= xx < w and 0 <= yy < h and (xx + 0.5 - x) ** 2 + (yy + 0.5 - y) ** 2 <= radius * radius:
                    i = 3 * (yy * w + xx)
                    pixels[i:i + 3] = bytes(colour)

    for label in order:
        pts = lines[label]
        (x0, y0), (x1, y1) = pts[0], pts[-1]
        steps = int(math.hypot(x1 - x0, y1 - y0))
        for k in range(steps + 1):  # the chord: where a straight edge would run
            t = k / max(steps, 1)
            dot(x0 + (x1 - x0) * t, y0 + (y1 - y0) * t, (255, 230, 0), 1.0)
        for x, y in pts:
            dot(x, y, (0, 220, 235) if held else (230, 20, 30), 3.2)
    write_ppm(out, pixels, w, h)


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "scene":
        make_scene(sys.argv[2])
    elif len(sys.argv) in (5, 6) and sys.argv[1] == "overlay":
        overlay(sys.argv[2], sys.argv[3], sys.argv[4], len(sys.argv) == 6 and sys.argv[5] == "held")
    else:
        sys.exit(__doc__)

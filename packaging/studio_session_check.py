#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The studio session's truths and measures, made outside the code under test (numpy only).

  studio_session_check.py grid OUT.ppm CLICKS.txt   a square grid of SPACING px photographed
                                      through a barrel lens, and the photo points a user clicks
                                      to trace two horizontal and two vertical grid lines
  studio_session_check.py spacing IMAGE.ppm [ALPHA.pgm]   the grid lines' spacing in a corrected
                                      image, against SPACING: exit 1 unless every spacing is
                                      within 3 %
  studio_session_check.py lines PROJECT.artcamproj OUT.csv   a project's straight lines as the
                                      CSV `artcam fit --lines` reads (line,x,y); prints the
                                      project's line model ("auto" when it records none)
  studio_session_check.py mapdiff A.csv B.csv   the largest distance between two `artcam map`
                                      outputs of the same points (x,y,X,Y rows)
  studio_session_check.py project PHOTO PAIRS.txt OUT.artcamproj   a project of PHOTO with the
                                      pairs "sx sy tx ty" a line (what `artcam export
                                      --camera-out` turns into the studio's camera of them)
  studio_session_check.py inverse ARTCAM CAM.artcam X Y   the photo pixel CAM maps to (X, Y), by
                                      Newton's method on `artcam map` (forward only)
  studio_session_check.py anchors MAPPED.csv CLICKS.txt   depth points mapped to the result
                                      (`artcam map` rows) against the result pixels clicked

The lens is the division lens of the project's barrel pictures: the scene point of photo point u
is U = u / (1 - K |u|^2) in the normalised frame (u_n = (u - c) / s, c the frame's centre, s half
its longer side), so the photo samples the scene at U, and the grid's straightened image has its
lines SPACING px apart wherever the camera undoes exactly that lens. Pixel centres at i + 0.5.
"""
import csv
import json
import math
import sys

import numpy as np

W, H = 960, 720
SPACING = 90.0
K = 0.25
S = max(W, H) / 2.0
CX, CY = W / 2.0, H / 2.0
LINE_PX = 3.0  # the grid lines' width in the scene


def scene_from_photo(x, y):
    u, v = (x - CX) / S, (y - CY) / S
    d = 1.0 - K * (u * u + v * v)
    return CX + S * u / d, CY + S * v / d


def photo_from_scene(x, y):
    u, v = (x - CX) / S, (y - CY) / S
    f = 2.0 / (1.0 + math.sqrt(1.0 + 4.0 * K * (u * u + v * v)))
    return CX + S * u * f, CY + S * v * f


def write_pnm(path, pixels):
    kind = b"P6" if pixels.ndim == 3 else b"P5"
    with open(path, "wb") as f:
        f.write(b"%s\n%d %d\n255\n" % (kind, pixels.shape[1], pixels.shape[0]))
        f.write(np.ascontiguousarray(pixels, dtype=np.uint8).tobytes())


def read_pnm(path):
    with open(path, "rb") as f:
        data = f.read()
    fields, pos = [], 0
    while len(fields) < 4:  # magic, width, height, maxval; comments skipped
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos)
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    pos += 1
    w, h, maxval = int(fields[1]), int(fields[2]), int(fields[3])
    channels = 3 if fields[0] == b"P6" else 1
    dtype = np.uint8 if maxval < 256 else np.dtype(">u2")
    img = np.frombuffer(data, dtype=dtype, count=w * h * channels, offset=pos)
    img = img.reshape(h, w, channels).astype(np.float64) / maxval
    return img.mean(axis=2)


def grid(out_path, clicks_path):
    # 4x4 samples per pixel: the lines' antialiased edges let a measure find their centres to a
    # fraction of a pixel.
    n = 4
    sub = (np.arange(n) + 0.5) / n
    ys, xs = np.mgrid[0:H, 0:W].astype(np.float64)
    ink = np.zeros((H, W))
    for dy in sub:
        for dx in sub:
            u, v = (xs + dx - CX) / S, (ys + dy - CY) / S
            d = 1.0 - K * (u * u + v * v)
            sx, sy = CX + S * u / d, CY + S * v / d
            # Distance to the nearest grid line, in scene pixels, along each axis.
            gx = np.abs((sx - CX + SPACING / 2) % SPACING - SPACING / 2)
            gy = np.abs((sy - CY + SPACING / 2) % SPACING - SPACING / 2)
            ink += ((gx < LINE_PX / 2) | (gy < LINE_PX / 2)).astype(np.float64)
    ink /= n * n
    paper = np.array([236.0, 230.0, 214.0])
    line = np.array([32.0, 36.0, 48.0])
    rgb = paper[None, None, :] * (1 - ink[..., None]) + line[None, None, :] * ink[..., None]
    write_pnm(out_path, np.clip(np.rint(rgb), 0, 255))

    # The plumb-line set: two horizontals three grid lines above and below the centre, two
    # verticals four grid lines left and right of it, each clicked at 8 points along it.
    with open(clicks_path, "w") as f:
        for name, horizontal, at in (("top", True, CY - 3 * SPACING),
                                     ("bottom", True, CY + 3 * SPACING),
                                     ("left", False, CX - 4 * SPACING),
                                     ("right", False, CX + 4 * SPACING)):
            length = W if horizontal else H
            points = []
            for i in range(8):
                along = 24 + (length - 48) * i / 7.0
                x, y = photo_from_scene(along, at) if horizontal else photo_from_scene(at, along)
                points.append("%.2f,%.2f" % (x, y))
            f.write("%s %s\n" % (name, " ".join(points)))
    print("grid %dx%d, spacing %g px, division lens k %g; truth written beside: %s" %
          (W, H, SPACING, K, clicks_path))


def dark_centres(profile, valid):
    """Centres (intensity-weighted, in pixel-centre coordinates) of the dark runs of a profile
    that lie wholly where `valid` holds."""
    lo, hi = np.percentile(profile[valid], 2), np.percentile(profile[valid], 98)
    if hi - lo < 0.2:
        return []
    threshold = (lo + hi) / 2
    dark = (profile < threshold) & valid
    centres, i, n = [], 0, len(profile)
    while i < n:
        if not dark[i]:
            i += 1
            continue
        j = i
        while j < n and dark[j]:
            j += 1
        a, b = max(i - 2, 0), min(j + 2, n)
        if a > 0 and b < n and valid[a:b].all() and j - i < 12:
            w = np.clip(hi - profile[a:b], 0, None)
            centres.append(float((w * (np.arange(a, b) + 0.5)).sum() / w.sum()))
        i = j
    return centres


def spacing(image_path, alpha_path=None):
    img = read_pnm(image_path)
    h, w = img.shape
    valid = read_pnm(alpha_path) > 0.99 if alpha_path else np.ones_like(img, dtype=bool)
    # Rows and columns through the middle of grid cells (half a spacing off the lines), so a
    # profile crosses only the lines across it.
    gaps, worst_profile = [], ""
    report = []
    for axis in ("row", "column"):
        centre, length = (CY, h) if axis == "row" else (CX, w)
        k = math.floor(-centre / SPACING)
        at_list = []
        while centre + (k + 0.5) * SPACING < length:
            at = centre + (k + 0.5) * SPACING
            if at > 10:
                at_list.append(int(at))
            k += 1
        for at in at_list:
            profile = img[at, :] if axis == "row" else img[:, at]
            ok = valid[at, :] if axis == "row" else valid[:, at]
            c = dark_centres(profile, ok)
            d = np.diff(c)
            d = d[d < 1.6 * SPACING]  # a line the threshold missed is not a double spacing
            if len(d) == 0:
                continue
            gaps.extend(d.tolist())
            report.append("%s %d: %d lines, spacing %.1f-%.1f px" % (axis, at, len(c), d.min(),
                                                                     d.max()))
    if not gaps:
        print("spacing: no grid lines found in %s" % image_path)
        return 1
    g = np.array(gaps)
    worst = float(np.abs(g / SPACING - 1).max())
    for line in report:
        print("  " + line)
    print("spacing of %d neighbouring lines: mean %.2f px, min %.2f, max %.2f (truth %g):"
          " worst %.2f %% off" % (len(g), g.mean(), g.min(), g.max(), SPACING, 100 * worst))
    return 0 if worst <= 0.03 else 1


def lines(project_path, out_path):
    with open(project_path) as f:
        project = json.load(f)
    traced = project.get("lines", [])
    with open(out_path, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["line", "x", "y"])
        for i, line in enumerate(traced):
            if not line.get("enabled", True):
                continue
            label = line.get("label") or str(i + 1)
            for x, y in line["points"]:
                out.writerow([label, repr(float(x)), repr(float(y))])
    print(project.get("line_model", "auto"))
    sys.stderr.write("lines: %d traced lines, %d points\n" %
                     (len(traced), sum(len(l["points"]) for l in traced)))
    return 0


def read_mapped(path):
    rows = []
    with open(path) as f:
        for row in csv.reader(f):
            try:
                rows.append([float(v) for v in row[:4]])
            except ValueError:
                continue  # the header
    return np.array(rows)


def mapdiff(a_path, b_path):
    a, b = read_mapped(a_path), read_mapped(b_path)
    if a.shape != b.shape or len(a) == 0:
        print("mapdiff: %s and %s map different points" % (a_path, b_path))
        return 1
    d = np.hypot(a[:, 2] - b[:, 2], a[:, 3] - b[:, 3])
    print("%d points: max %.3g px, mean %.3g px" % (len(d), d.max(), d.mean()))
    return 0 if d.max() < 0.01 else 1


def anchors(mapped_path, clicks_path):
    """Depth points clicked on the result land where the result shows them: each point's photo
    pixel, mapped by the project's camera, is the result pixel that was clicked."""
    mapped = read_mapped(mapped_path)
    clicks = []
    with open(clicks_path) as f:
        for line in f:
            clicks.append([float(v) for v in line.split()])
    clicks = np.array(clicks)
    if len(mapped) != len(clicks):
        print("anchors: %d depth points in the project, %d clicked" % (len(mapped), len(clicks)))
        return 1
    d = np.hypot(mapped[:, 2] - clicks[:, 0], mapped[:, 3] - clicks[:, 1])
    print("%d depth points: mapped to the result, max %.2f px from the click" % (len(d), d.max()))
    return 0 if d.max() < 1.5 else 1


def project(photo, pairs_path, out_path):
    pairs = []
    with open(pairs_path) as f:
        for line in f:
            v = [float(x) for x in line.split()]
            if len(v) == 4:
                pairs.append({"source": v[0:2], "target": v[2:4], "enabled": True})
    with open(out_path, "w") as f:
        json.dump({"format": "artcam-studio-project", "version": 1, "photo": photo,
                   "model": "auto", "pairs": pairs}, f)
    return 0


def inverse(artcam, camera, x, y):
    import os
    import subprocess
    import tempfile
    target = np.array([float(x), float(y)])
    p = target.copy()  # the start: the camera moves points by a few pixels
    h = 0.5
    fd, points = tempfile.mkstemp(suffix=".csv")
    os.close(fd)
    try:
        for _ in range(20):
            with open(points, "w") as f:
                f.write("x,y\n%r,%r\n%r,%r\n%r,%r\n" % (p[0], p[1], p[0] + h, p[1], p[0], p[1] + h))
            out = subprocess.run([artcam, "map", camera, points], capture_output=True, text=True,
                                 check=True).stdout.strip().split("\n")
            m = np.array([[float(v) for v in row.split(",")[2:4]] for row in out[-3:]])
            jac = np.column_stack(((m[1] - m[0]) / h, (m[2] - m[0]) / h))
            step = np.linalg.solve(jac, target - m[0])
            p = p + step
            if np.hypot(*step) < 1e-4:
                break
    finally:
        os.remove(points)
    print("%.3f %.3f" % (p[0], p[1]))
    return 0


def main(argv):
    commands = {"grid": grid, "spacing": spacing, "lines": lines, "mapdiff": mapdiff,
                "project": project, "inverse": inverse, "anchors": anchors}
    if len(argv) < 2 or argv[1] not in commands:
        sys.stderr.write(__doc__)
        return 2
    return commands[argv[1]](*argv[2:])


if __name__ == "__main__":
    sys.exit(main(sys.argv))

#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Writes the hand-made seeds of fuzz/corpus/<target>/ (seed-*) and the known nasty inputs
(nasty-*): valid files of every shape each reader takes, made here from resources/ and from
the grammars in core/io/*.h, plus inputs that once crashed, hung or allocated too much.
Inputs that libFuzzer found are added by `fuzz/run_fuzzers.sh` (minimised, named by hash).
Run from the repository root: python3 fuzz/make_seeds.py"""
import base64
import json
import os
import struct

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CORPUS = os.path.join(ROOT, "fuzz", "corpus")


def put(target, name, data):
    os.makedirs(os.path.join(CORPUS, target), exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    with open(os.path.join(CORPUS, target, name), "wb") as f:
        f.write(data)


def resource(path):
    with open(os.path.join(ROOT, "resources", path), "rb") as f:
        return f.read()


def identity_tensors(n, unit):
    """x Q_i x^T = x_i * x_unit: the identity camera (README, "Decisions")."""
    tensors = []
    for i in range(n):
        q = [[0.0] * n for _ in range(n)]
        q[i][unit] += 0.5
        q[unit][i] += 0.5
        tensors.append(q)
    return tensors


def camera(blocks, w=64, h=48, **extra):
    n = sum(size for _, size in blocks)
    doc = {"format": "artcam", "version": 1,
           "blocks": [{"kind": k, "size": s} for k, s in blocks],
           "frames": {"source": [w, h], "target": [w, h]},
           "stages": [{"tensors": identity_tensors(n, 2)}]}
    doc.update(extra)
    return doc


# ---- .artcam ----
put("artcam", "seed-sample.artcam", resource("sample.artcam"))
put("artcam", "seed-identity.artcam", json.dumps(camera([("position", 3)])))
fit = {"model": "homography", "matches": 4, "rms_px": 0.5, "max_px": 1, "residuals_px": [0.5, 0.25],
       "singular_values": [1, 0.5], "reason": "auto", "held_out_rms_px": 0.75,
       "pole_free": True, "pole_margin": 0.125, "inliers": [0, 1, 3]}
matches = [{"source": [1, 2], "target": [3, 4], "enabled": False}, {"source": [5, 6], "target": [7, 8]}]
put("artcam", "seed-fit.artcam", json.dumps(camera([("position", 3)], matches=matches, fit=fit)))
colour = camera([("position", 3), ("colour", 4)])
colour["layers"] = [{"stages": colour["stages"]}, {"stages": colour["stages"]}]
put("artcam", "seed-layers.artcam", json.dumps(colour))
put("artcam", "seed-depth.artcam",
    json.dumps(camera([("position", 3), ("colour", 4), ("depth", 2)], depth_output="blur-variance")))
chain = camera([("position", 3)])
chain["stages"] = chain["stages"] * 2
put("artcam", "seed-chain.artcam", json.dumps(chain))
# Nasty: stack-deep nesting, overflowing literals, giant frames, and n empty rows that once
# made the reader allocate the n×n tensor before reading a row.
put("artcam", "nasty-deep-nesting.artcam", "[" * 2000)
put("artcam", "nasty-deep-object.artcam", '{"a":' * 2000)
put("artcam", "nasty-overflow.artcam", json.dumps(camera([("position", 3)])).replace("0.5", "1e999", 1))
put("artcam", "nasty-nan.artcam", json.dumps(camera([("position", 3)])).replace("0.5", "NaN", 1))
put("artcam", "nasty-giant-frame.artcam",
    json.dumps(camera([("position", 3)], w=2147483648, h=2147483647)))
put("artcam", "nasty-frame-negative.artcam", json.dumps(camera([("position", 3)], w=-1)))
# One pixel past kMaxFrameSide (core/model/artcam.h): a camera no command can write or render.
put("artcam", "nasty-frame-over-limit.artcam", json.dumps(camera([("position", 3)], w=(1 << 20) + 1)))
big = camera([("position", 3)])
big["blocks"] = big["blocks"] * 3000
big["stages"] = [{"tensors": [[[]] * 9000] + [0] * 8999}]
put("artcam", "nasty-empty-rows.artcam", json.dumps(big).replace(" ", ""))
put("artcam", "nasty-kind-newline.artcam",
    json.dumps(camera([("position", 3)])).replace('"position"', '"posi\\ntion"', 1))
put("artcam", "nasty-version.artcam", json.dumps(dict(camera([("position", 3)]), version=99999999999999999999)))

# ---- piecewise .artcam ----
whole = camera([("position", 3)], w=64, h=64)
patch = {"rect": [0, 0, 32, 64], "support": [[1, 1], [30, 1], [30, 60]], "model": "homography",
         "matches": 3, "rms_px": 0.1, "max_px": 0.2, "camera": camera([("position", 3)], w=64, h=64)}
patch2 = dict(patch, rect=[32, 0, 64, 64])
put("piecewise", "seed-two-patches.artcam",
    json.dumps(dict(whole, support_margin_px=4, patches=[patch, patch2])))
put("piecewise", "seed-plain.artcam", resource("sample.artcam"))
put("piecewise", "nasty-model-not-string.artcam", json.dumps(dict(whole, patches=[dict(patch, model=7)])))
put("piecewise", "nasty-deep-camera.artcam",
    json.dumps(dict(whole, patches=[dict(patch, camera={})])).replace('"camera": {}', '"camera": ' + '{"a":' * 2000 + "1" + "}" * 2000))

# ---- match CSV (2D unless the header names src_z) ----
put("matches_csv", "seed-sample.csv", resource("sample-matches.csv"))
put("matches_csv", "seed-3d.csv", "src_x,src_y,src_z,dst_x,dst_y,dst_z\n1,2,3,4,5,6\n-1e-300,+2.5,0,1e9,5,6\n")
put("matches_csv", "seed-enabled.csv",
    "\ufeffSRC_X,src_y,dst_x,dst_y,enabled\r\n# a comment\r\n\r\n 1 , 2 ,3,4,1\r\n5,6,7,8,false\r\n9,10,11,12,true")
put("matches_csv", "nasty-out-of-range.csv", "src_x,src_y,dst_x,dst_y\n1e999,2,3,4\n")
put("matches_csv", "nasty-inf.csv", "src_x,src_y,dst_x,dst_y\ninf,2,3,nan\n")
put("matches_csv", "nasty-commas.csv", "src_x,src_y,dst_x,dst_y\n" + "," * 5000 + "\n")
# Traced lines (line,x,y: parseLinesCsv when the header starts "line"): a seed, and 5 000
# lines of one point each, whose label search once grew with the square of the rows.
put("matches_csv", "seed-lines.csv", "line,x,y\ntop,10,20\ntop,300,25\ntop,590,20\nleft,10,20\nleft,14,200\n")
put("matches_csv", "nasty-lines-many.csv",
    "line,x,y\n" + "".join("L%d,%d.5,1.5\n" % (k, k % 64) for k in range(5000)))

# ---- colour-sample CSV (sRGB-encoded when the input's size is odd) ----
put("colour_csv", "seed-linear.csv",
    "src_r,src_g,src_b,dst_r,dst_g,dst_b\n0.1,0.2,0.3,0.15,0.2,0.25\n1.5,-0.1,0,1,1,1\n")
put("colour_csv", "seed-srgb-enabled.csv",
    "src_r,src_g,src_b,dst_r,dst_g,dst_b,enabled\n0.5,0.5,0.5,0.4,0.5,0.6,1\n1,0,0,0.9,0.1,0,0\n ")
put("colour_csv", "nasty-srgb-huge.csv", "src_r,src_g,src_b,dst_r,dst_g,dst_b\n1e308,1,1,1,1,-1e308\n")

# ---- PLY ----
def ply_header(fmt, count, props, extra=""):
    lines = ["ply", "format %s 1.0" % fmt, "comment seed", extra.strip()] if extra else ["ply", "format %s 1.0" % fmt]
    lines = [l for l in lines if l]
    lines.append("element vertex %d" % count)
    lines += ["property %s %s" % (t, n) for t, n in props]
    lines.append("end_header")
    return "\n".join(lines) + "\n"


xyz_rgb = [("float", "x"), ("float", "y"), ("float", "z"), ("uchar", "red"), ("uchar", "green"), ("uchar", "blue")]
points = [(0.0, 0.0, 0.0, 255, 0, 0), (1.0, 0.5, -2.0, 0, 255, 0), (0.25, 1e-3, 3.5, 0, 0, 255)]
put("ply", "seed-ascii.ply", ply_header("ascii", 3, xyz_rgb) + "".join("%g %g %g %d %d %d\n" % p for p in points))
put("ply", "seed-binary-le.ply", ply_header("binary_little_endian", 3, xyz_rgb).encode()
    + b"".join(struct.pack("<fffBBB", *p) for p in points))
put("ply", "seed-binary-be.ply", ply_header("binary_big_endian", 3, xyz_rgb).encode()
    + b"".join(struct.pack(">fffBBB", *p) for p in points))
rgba = [("double", "x"), ("double", "y"), ("double", "z"), ("float", "red"), ("float", "green"),
        ("float", "blue"), ("float", "alpha"), ("short", "confidence")]
put("ply", "seed-double-alpha.ply", ply_header("binary_little_endian", 2, rgba).encode()
    + struct.pack("<dddffffh", 1, 2, 3, 0.5, 0.25, 0.125, 0.5, 7) * 2)
faces = "element face 1\nproperty list uchar int vertex_indices\n"
put("ply", "seed-faces-first.ply",
    (ply_header("binary_little_endian", 2, [("float", "x"), ("float", "y"), ("float", "z")],
                extra=faces)).encode().replace(b"element face 1\nproperty list uchar int vertex_indices\nelement vertex 2",
                                               b"element face 1\nproperty list uchar int vertex_indices\nelement vertex 2")
    + struct.pack("<Biii", 3, 0, 1, 1) + struct.pack("<fff", 1, 2, 3) * 2)
cube = resource("cube.ply")
end = cube.index(b"end_header\n") + len(b"end_header\n")
put("ply", "seed-cube-head.ply", cube[:end].replace(b"element vertex 16200", b"element vertex 40") + cube[end:end + 40 * 15])
put("ply", "nasty-trillion-vertices.ply", ply_header("binary_little_endian", 10**12, xyz_rgb).encode() + b"\0" * 30)
put("ply", "nasty-count-overflow.ply", ply_header("ascii", 2**64 - 1, xyz_rgb) + "1 2 3 4 5 6\n")
put("ply", "nasty-list-count.ply",
    b"ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list uint int v\nelement vertex 1\n"
    b"property float x\nproperty float y\nproperty float z\nend_header\n" + struct.pack("<I", 0xFFFFFFFF) + b"\0" * 12)

# ---- studio project ----
put("project", "seed-sample.artcamproj", resource("sample.artcamproj"))
mask = base64.b64encode(bytes([0, 5, 255, 3])).decode()
project = {"format": "artcam-studio-project", "version": 2, "photo": "photo.png", "model": "homography",
           "pairs": [{"source": [1, 2], "target": [3, 4], "enabled": False}],
           "camera": camera([("position", 3)]),
           "view": {"scale": 2, "centre": [10, 20], "preview_mode": 1, "opacity": 0.25},
           "parts": {"insertion": {"graphic": "emblem.png"}},
           "depth": {"layers": [{"name": "Plane 1", "size": [4, 2], "mask": mask,
                                 "anchors": [{"pixel": [0.5, 0.5], "depth": 2},
                                             {"pixel": [3.5, 0.5], "depth": 3},
                                             {"pixel": [0.5, 1.5], "depth": 4}]}],
                     "map": {"path": "depth.exr", "scale": 0.5, "inverse": True}}}
put("project", "seed-depth.artcamproj", json.dumps(project, indent=1))
giant = json.loads(json.dumps(project))
giant["depth"]["layers"][0]["size"] = [46340, 46340]
put("project", "nasty-giant-mask.artcamproj", json.dumps(giant))
lying = json.loads(json.dumps(project))
lying["depth"]["layers"][0]["size"] = [30000, 30000]
put("project", "nasty-lying-mask.artcamproj", json.dumps(lying))
bad_view = json.loads(json.dumps(project))
bad_view["view"]["preview_mode"] = 1000000
put("project", "nasty-preview-mode.artcamproj", json.dumps(bad_view))
# A bomb: 12 layers of 32768^2 masks, each one run-length run (8 characters), 12 GiB asked of
# 2 KB; refused by the whole-document budget before any mask is decoded.
_side = 32768
_run = bytearray([0])
_n = _side * _side
while True:
    _run.append((_n & 0x7F) | (0x80 if _n >= 0x80 else 0))
    _n >>= 7
    if _n == 0:
        break
bomb = json.loads(json.dumps(project))
bomb["depth"]["layers"] = [{"name": "p", "size": [_side, _side],
                            "mask": base64.b64encode(bytes(_run)).decode(), "anchors": []}] * 12
put("project", "nasty-mask-bomb.artcamproj", json.dumps(bomb))
# More effects than a stack may hold (kMaxProjectEffects): refused, not worked through.
many_effects = dict(project, version=3, effects=[{"effect": "twist", "params": {"rate": [0.001]}}] * 300)
put("project", "nasty-effects-over-limit.artcamproj", json.dumps(many_effects))
# A match far beyond any pixel (kMaxMatchValue): once fitted to the identity without a word.
huge_match = json.loads(json.dumps(project))
huge_match["pairs"] = [{"source": [1e300, 2], "target": [3, 4]}]
put("project", "nasty-huge-match.artcamproj", json.dumps(huge_match))
put("project", "nasty-deep-nesting.artcamproj", '{"a":' * 5000 + "1" + "}" * 5000)
put("project", "nasty-deep-camera.artcamproj",
    json.dumps(dict(project, camera={})).replace('"camera": {}', '"camera": ' + '{"a":' * 1000 + "1" + "}" * 1000))

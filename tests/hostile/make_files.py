#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Makes the hostile corpus's input files (tests/hostile/cases.tsv names them) in one folder.

Every file is made here, from code, so the corpus holds no binary blobs and each file says how
it was built: valid images come from oiiotool (OpenImageIO's own tool, an independent writer),
hostile ones are valid files cut, patched or padded byte by byte. Files stay small (the biggest
is a 64 KiB padded header): a claim of size, not the bytes, is what makes them hostile.

Files for one area's cases (cases-<area>.tsv) are made by files_<area>.py beside this script,
run last with this script's names (put, get, oiio, camera, project, ...) in scope.

usage: make_files.py OUT_DIR RESOURCES_DIR ARTCAM
"""
import json
import os
import shutil
import struct
import subprocess
import sys
import zlib

out, resources, artcam = sys.argv[1], sys.argv[2], sys.argv[3]
os.makedirs(out, exist_ok=True)


def put(name, data):
    with open(os.path.join(out, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def get(name):
    with open(os.path.join(out, name), "rb") as f:
        return f.read()


def oiio(name, *args):
    subprocess.run(["oiiotool", *args, "-o", os.path.join(out, name)], check=True,
                   stdout=subprocess.DEVNULL)


# --- images -------------------------------------------------------------------------------------
oiio("ok.png", "--pattern", "fill:topleft=1,0,0:topright=0,1,0:bottomleft=0,0,1:bottomright=1,1,1",
     "64x48", "3")
oiio("ok.jpg", "--pattern", "fill:top=0.2,0.4,0.6:bottom=0.8,0.6,0.4", "64x48", "3")
oiio("ok.tif", "--pattern", "checker:width=8:height=8", "64x48", "3")
oiio("ok.exr", "--pattern", "fill:top=0.1,0.2,0.3,1:bottom=0.9,0.8,0.7,1", "64x48", "4", "-d", "half")
oiio("five.tif", "--pattern", "constant:color=0.1,0.2,0.3,1,0.5", "64x48", "5")
# An EXR of 40 channels (RGBA, Z and 35 AOVs): every one is warped into an EXR.
forty = ["R", "G", "B", "A", "Z"] + ["aov%d.%s" % (k // 3, "RGB"[k % 3]) for k in range(35)]
oiio("forty.exr", "--pattern", "constant:color=" + ",".join("%.2f" % (0.02 * k) for k in range(40)),
     "64x48", "40", "--chnames", ",".join(forty), "-d", "half")
# Data windows that are not the display window: one outside it, one a crop inside it.
oiio("window-outside.exr", "--pattern", "constant:color=0.5,0.5,0.5", "32x24", "3",
     "--origin", "+100+100", "--fullsize", "64x48+0+0", "-d", "half")
oiio("window-inside.exr", "--pattern", "constant:color=0.5,0.5,0.5", "32x24", "3",
     "--origin", "+8+4", "--fullsize", "64x48+0+0", "-d", "half")
oiio("gray.png", "--pattern", "fill:top=0:bottom=1", "64x48", "1")
oiio("gray-alpha.png", "--pattern", "constant:color=0.5,1", "64x48", "2")
oiio("one-pixel.png", "--pattern", "constant:color=0.5,0.5,0.5", "1x1", "3")
oiio("rgba16.png", "--pattern", "constant:color=0.5,0.5,0.5,1", "64x48", "4", "-d", "uint16")
oiio("depth.exr", "--pattern", "fill:top=1:bottom=5", "64x48", "1", "-d", "float")
oiio("depth.tif", "--pattern", "fill:top=1:bottom=5", "64x48", "1", "-d", "float")
oiio("depth16.png", "--pattern", "fill:top=0.01:bottom=0.1", "64x48", "1", "-d", "uint16")
oiio("depth-small.exr", "--pattern", "constant:color=2", "16x12", "1", "-d", "float")
oiio("depth-rgb.exr", "--pattern", "constant:color=2,2,2", "64x48", "3", "-d", "float")
oiio("depth-zero.exr", "--pattern", "constant:color=0", "64x48", "1", "-d", "float")
oiio("depth-negative.exr", "--pattern", "constant:color=-3", "64x48", "1", "-d", "float")
oiio("stmap.exr", "--pattern", "fill:topleft=0,1,0,1:topright=1,1,0,1:bottomleft=0,0,0,1:"
     "bottomright=1,0,0,1", "64x48", "4", "-d", "float")
oiio("stmap-empty.exr", "--pattern", "constant:color=0,0,0,0", "64x48", "4", "-d", "float")

png, jpg, tif, exr = get("ok.png"), get("ok.jpg"), get("ok.tif"), get("ok.exr")
put("cut-half.png", png[: len(png) // 2])
put("cut-header.png", png[:20])
put("cut-half.jpg", jpg[: len(jpg) // 2])
put("cut-half.tif", tif[: len(tif) // 2])
put("cut-half.exr", exr[: len(exr) // 2])
put("cut-header.exr", exr[:40])
depth_tif = get("depth.tif")
put("depth-cut.tif", depth_tif[: len(depth_tif) // 2])
depth_exr = get("depth.exr")
put("depth-cut.exr", depth_exr[: len(depth_exr) // 2])
put("empty.png", b"")
put("text.png", "this is not a picture\n")
put("text.jpg", "not a jpeg either\n")
put("gif-length.gif", b"GIF89a" + b"\xff\xff\xff\xff" + b"\x00" * 24)
put("zeros.tif", b"\x00" * 4096)
os.makedirs(os.path.join(out, "folder.png"), exist_ok=True)


def png_chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def png_with(width, height, pad=0, depth=8, colour=2):
    ihdr = struct.pack(">IIBBBBB", width, height, depth, colour, 0, 0, 0)
    body = png_chunk(b"IHDR", ihdr)
    if pad:
        body += png_chunk(b"IDAT", zlib.compress(b"\x00" * pad))
    return b"\x89PNG\r\n\x1a\n" + body + png_chunk(b"IEND", b"")


put("giant-header.png", png_with(100000, 100000))
put("giant-padded.png", png_with(30000, 30000, pad=64 * 1024))
put("zero-size.png", png_with(0, 0))
put("wide-line.png", png_with(2**31 - 1, 1))
put("bad-depth.png", png_with(64, 48, depth=3))
put("bad-crc.png", png[:29] + bytes([png[29] ^ 0xFF]) + png[30:])


def tiff_with(width, height, pad=0):
    # A little-endian baseline TIFF header: width, length, 8-bit RGB, one strip at the end.
    entries = [(256, 4, 1, width), (257, 4, 1, height), (258, 3, 1, 8), (259, 3, 1, 1),
               (262, 3, 1, 2), (273, 4, 1, 8 + 2 + 12 * 11 + 4), (277, 3, 1, 3),
               (278, 4, 1, height), (279, 4, 1, pad), (284, 3, 1, 1), (339, 3, 1, 1)]
    ifd = struct.pack("<H", len(entries))
    for tag, kind, count, value in entries:
        ifd += struct.pack("<HHII", tag, kind, count, value)
    return b"II*\x00" + struct.pack("<I", 8) + ifd + struct.pack("<I", 0) + b"\x00" * pad




def tiff_with_icc(icc, width=4, height=2):
    # A 4x2 8-bit RGB TIFF carrying `icc` as its ICC profile (tag 34675): the profile is what
    # the case is about, the pixels are fine.
    pixels = bytes(range(width * height * 3))
    count = 12
    icc_at = 8 + 2 + 12 * count + 4
    strip_at = icc_at + len(icc)
    entries = [(256, 4, 1, width), (257, 4, 1, height), (258, 3, 1, 8), (259, 3, 1, 1),
               (262, 3, 1, 2), (273, 4, 1, strip_at), (277, 3, 1, 3), (278, 4, 1, height),
               (279, 4, 1, len(pixels)), (284, 3, 1, 1), (339, 3, 1, 1),
               (34675, 7, len(icc), icc_at)]
    assert len(entries) == count
    ifd = struct.pack("<H", count)
    for tag, kind, n, value in entries:
        ifd += struct.pack("<HHII", tag, kind, n, value)
    return b"II*\x00" + struct.pack("<I", 8) + ifd + struct.pack("<I", 0) + icc + pixels


def icc_header(size, space=b"RGB ", tags=0):
    # An ICC v2 display-class header (128 bytes) and a tag count: what a profile opens with.
    header = struct.pack(">I", size) + b"lcms" + bytes([2, 0x10, 0, 0]) + b"mntr" + space
    header += b"XYZ " + bytes(12) + b"acsp" + bytes(128 - 40)
    return header + struct.pack(">I", tags)


# A profile that is noise after its signature, one whose tag table points past its end, and a
# CMYK header on RGB pixels.
put("icc-noise.tif", tiff_with_icc(b"acsp" + bytes((i * 37) % 256 for i in range(300))))
put("icc-cut.tif", tiff_with_icc(icc_header(4000, tags=3)
                                  + struct.pack(">4sII", b"rXYZ", 3000, 20) * 3))
put("icc-cmyk.tif", tiff_with_icc(icc_header(132, space=b"CMYK")))

put("giant-header.tif", tiff_with(2**31 - 1, 2**31 - 1))
put("giant-padded.tif", tiff_with(40000, 40000, pad=64 * 1024))
put("zero-size.tif", tiff_with(0, 0, pad=16))
# A JPEG whose frame header claims 65500x65500: the SOF0 segment of the valid file patched.
sof = jpg.find(b"\xff\xc0")
put("giant-header.jpg", jpg[: sof + 5] + struct.pack(">HH", 65500, 65500) + jpg[sof + 9:]
    + b"\x00" * 65536)
# An EXR whose dataWindow claims 2^30 x 2^30 pixels (the attribute patched in place).
dw = exr.find(b"dataWindow\x00box2i\x00")
at = dw + len(b"dataWindow\x00box2i\x00") + 4
put("giant-header.exr", exr[:at] + struct.pack("<iiii", 0, 0, 2**30, 2**30) + exr[at + 16:])
put("inverted-window.exr", exr[:at] + struct.pack("<iiii", 10, 10, 0, 0) + exr[at + 16:])

# --- cameras (.artcam) --------------------------------------------------------------------------
IDENT = [[[0, 0, 0.5], [0, 0, 0], [0.5, 0, 0]],
         [[0, 0, 0], [0, 0, 0.5], [0, 0.5, 0]],
         [[0, 0, 0], [0, 0, 0], [0, 0, 1]]]


def camera(tensors=None, source=(64, 48), target=(64, 48), **extra):
    d = {"format": "artcam", "version": 1, "blocks": [{"kind": "position", "size": 3}],
         "frames": {"source": list(source), "target": list(target)},
         "stages": [{"tensors": tensors if tensors is not None else IDENT}]}
    d.update(extra)
    return d


def put_json(name, value):
    put(name, json.dumps(value))


def denominator(q):
    return [IDENT[0], IDENT[1], q]


put_json("identity.artcam", camera())
# A shift by 1.2 normalised units (60 % of the width): alone it covers 40 % of the frame, twice
# nothing (the composition that lands nowhere).
put_json("shift.artcam", camera([[[0, 0, 0.5], [0, 0, 0], [0.5, 0, 1.2]],
                                 [[0, 0, 0], [0, 0, 0.5], [0, 0.5, 0]],
                                 [[0, 0, 0], [0, 0, 0], [0, 0, 1]]]))
shutil.copy(os.path.join(resources, "sample.artcam"), os.path.join(out, "sample.artcam"))
put_json("zero.artcam", camera([[[0] * 3] * 3] * 3))
put_json("zero-denominator.artcam", camera(denominator([[0] * 3] * 3)))
# The denominator u (the normalised frame is centred): its pole line splits the frame in two.
put_json("pole-across.artcam", camera(denominator([[0, 0, 0.5], [0, 0, 0], [0.5, 0, 0]])))
# u² + v² - 0.04: a disc of poles around the centre (a partial pole).
put_json("pole-partial.artcam", camera(denominator([[1, 0, 0], [0, 1, 0], [0, 0, -0.04]])))
# u + 0.2: a pole line across the frame's height; the right side still renders.
put_json("pole-split.artcam", camera(denominator([[0, 0, 0.5], [0, 0, 0], [0.5, 0, 0.2]])))
# u + 2.5: no pole inside the frame (|u| <= 1), a plain homography.
put_json("pole-outside.artcam", camera(denominator([[0, 0, 0.5], [0, 0, 0], [0.5, 0, 2.5]])))
# -1 everywhere: the whole frame behind the camera (a negative, constant denominator).
put_json("negative-denominator.artcam", camera(denominator([[0, 0, 0], [0, 0, 0], [0, 0, -1]])))
put_json("huge-tensor.artcam", camera([[[1e308] * 3] * 3] * 3))
put_json("tiny-tensor.artcam", camera([[[1e-308 * e for e in row] for row in q] for q in IDENT]))
put_json("rank-one.artcam", camera([IDENT[2], IDENT[2], IDENT[2]]))
put_json("frame-zero.artcam", camera(source=(0, 0)))
put_json("frame-negative.artcam", camera(source=(-64, 48)))
put_json("frame-giant.artcam", camera(source=(2**30, 2**30)))
put_json("frame-fraction.artcam", camera(source=(64.5, 48)))
put_json("frame-string.artcam", camera(source=("64", 48)))
put_json("frame-target-zero.artcam", camera(target=(0, 48)))
put_json("frame-one-number.artcam", camera(source=(64,)))
put("nan.artcam", json.dumps(camera()).replace("0.5", "NaN", 1))
put("inf.artcam", json.dumps(camera()).replace("0.5", "1e999", 1))
put("bad-json.artcam", json.dumps(camera())[:-7])
put("empty.artcam", "")
put("not-json.artcam", "format: artcam\n")
put("deep.artcam", "[" * 100000 + "]" * 100000)
put("deep-object.artcam", '{"a":' * 5000 + "1" + "}" * 5000)
put("utf16.artcam", "\ufeff".encode("utf-16-le") + json.dumps(camera()).encode("utf-16-le"))
put("bom.artcam", b"\xef\xbb\xbf" + json.dumps(camera()).encode())
put("binary.artcam", bytes(range(256)) * 4)
put_json("version-99.artcam", dict(camera(), version=99))
put_json("format-wrong.artcam", dict(camera(), format="artcam-studio-project"))
put_json("no-stages.artcam", dict(camera(), stages=[]))
put_json("no-blocks.artcam", dict(camera(), blocks=[]))
put_json("wrong-tensor-count.artcam", camera(IDENT[:2]))
put_json("wrong-tensor-size.artcam", camera([[[0, 0], [0, 0]]] * 3))
put_json("ragged-tensor.artcam", camera([[[0, 0, 0.5], [0, 0], [0.5, 0, 0]], IDENT[1], IDENT[2]]))
put_json("block-unknown.artcam", dict(camera(), blocks=[{"kind": "smell", "size": 3}]))
# A second image's colour block with a wrong size, and one without the colour it blends into.
put_json("second-size.artcam", dict(camera(), blocks=[
    {"kind": "position", "size": 3}, {"kind": "colour", "size": 4},
    {"kind": "second-colour", "size": 3}]))
put_json("second-alone.artcam", dict(camera([[[0] * 7] * 7] * 7), blocks=[
    {"kind": "position", "size": 3}, {"kind": "second-colour", "size": 4}]))
put_json("block-size-huge.artcam", dict(camera(), blocks=[{"kind": "position", "size": 2**31 - 1}]))
put_json("number-as-string.artcam", camera([[["0", 0, 0.5], [0, 0, 0], [0.5, 0, 0]], IDENT[1],
                                           IDENT[2]]))
put_json("top-array.artcam", [camera()])
put_json("many-stages.artcam", dict(camera(), stages=[{"tensors": IDENT}] * 3000))
put_json("layers-empty.artcam", dict(camera(), layers=[]))
put_json("layers-bad.artcam", dict(camera(), layers=[{"stages": [{"tensors": IDENT[:1]}]}]))
put_json("fit-nan-margin.artcam", dict(camera(), fit={"model": "quadratic", "pole_margin": None,
                                                      "rms_px": "x"}))
put("duplicate-key.artcam", json.dumps(camera())[:-1] + ', "version": 2}')

# --- piecewise cameras --------------------------------------------------------------------------


def patch(rect, tensors=None, source=(64, 48)):
    return {"rect": rect, "support": [[1, 1], [30, 1], [30, 40]], "model": "homography",
            "matches": 3, "rms_px": 0.1, "max_px": 0.2, "camera": camera(tensors, source=source)}


def piecewise(patches, **extra):
    return camera(support_margin_px=4, patches=patches, **extra)


put_json("pw-ok.artcam", piecewise([patch([0, 0, 32, 48]), patch([32, 0, 64, 48])]))
put_json("pw-inverted.artcam", piecewise([patch([32, 48, 0, 0])]))
put_json("pw-empty-rect.artcam", piecewise([patch([10, 10, 10, 40])]))
put("pw-nan.artcam", json.dumps(piecewise([patch([0, 0, 32, 48])])).replace("[0, 0, 32, 48]",
                                                                             "[NaN, 0, 32, 48]"))
put("pw-inf.artcam", json.dumps(piecewise([patch([0, 0, 32, 48])])).replace("[0, 0, 32, 48]",
                                                                             "[0, 0, 1e999, 48]"))
put_json("pw-overlap.artcam", piecewise([patch([0, 0, 40, 48]), patch([20, 0, 64, 48])]))
put_json("pw-zero-camera.artcam", piecewise([patch([0, 0, 64, 48], [[[0] * 3] * 3] * 3)]))
put_json("pw-pole-camera.artcam", piecewise([patch([0, 0, 64, 48], denominator(
    [[0, 0, 0.5], [0, 0, 0], [0.5, 0, 0]]))]))
put_json("pw-outside.artcam", piecewise([patch([100, 100, 200, 200])]))
put_json("pw-partly-outside.artcam", piecewise([patch([-10, -10, 40, 40])]))
put_json("pw-2000.artcam", piecewise([patch([i % 64, (i // 64) % 48, i % 64 + 1,
                                             (i // 64) % 48 + 1]) for i in range(2000)]))
put_json("pw-1e308.artcam", piecewise([patch([0, 0, 1e308, 1e308])]))
put_json("pw-no-patches.artcam", piecewise([]))
put_json("pw-rect-short.artcam", piecewise([patch([0, 0, 32])]))
put_json("pw-patch-frame.artcam", piecewise([patch([0, 0, 64, 48], source=(640, 480))]))
put_json("pw-patches-object.artcam", piecewise({"rect": [0, 0, 1, 1]}))

# --- match and colour CSV -----------------------------------------------------------------------
shutil.copy(os.path.join(resources, "sample-matches.csv"), os.path.join(out, "matches.csv"))
rows = open(os.path.join(resources, "sample-matches.csv")).read().splitlines()
head, body = rows[0], rows[1:]
put("m-empty.csv", "")
put("m-header-only.csv", head + "\n")
put("m-no-header.csv", "\n".join(body) + "\n")
put("m-bad-row.csv", "\n".join([head] + body[:5] + ["1,2,three,4"] + body[5:]) + "\n")
put("m-short-row.csv", "\n".join([head] + body[:5] + ["1,2,3"] + body[5:]) + "\n")
put("m-nan.csv", "\n".join([head] + body[:5] + ["nan,2,3,4"] + body[5:]) + "\n")
put("m-inf.csv", "\n".join([head] + body[:5] + ["1,inf,3,4"] + body[5:]) + "\n")
put("m-1e300.csv", "\n".join([head] + body[:5] + ["1e300,2,3,4"] + body[5:]) + "\n")
put("m-two.csv", "\n".join([head] + body[:2]) + "\n")
put("m-duplicates.csv", "\n".join([head] + [body[0]] * 12) + "\n")
put("m-collinear.csv", "\n".join([head] + ["%d,%d,%d,%d" % (i, i, i + 1, i + 2)
                                           for i in range(12)]) + "\n")
put("m-crlf-bom.csv", ("\ufeff" + "\r\n".join([head] + body) + "\r\n").encode())
put("m-long-line.csv", head + "\n" + "1" * (1 << 20) + "\n")
put("m-binary.csv", bytes(range(256)) * 8)
put("m-enabled-2.csv", head + ",enabled\n" + "\n".join(r + ",2" for r in body) + "\n")
put("m-quoted.csv", head + "\n" + "\n".join('"' + r.replace(",", '","') + '"' for r in body) + "\n")
put("m-3d-2d.csv", "src_x,src_y,src_z,dst_x,dst_y,dst_z\n1,2,3,4,5,6\n")
put("points.csv", "x,y\n10,10\n32,24\n60,40\n")
put("points-nan.csv", "x,y\n10,10\nnan,24\n")
put("points-bad.csv", "x,y\n10\n")
put("points-two.csv", "x,y\n10,10\n32,24\n")
CHEAD = "src_r,src_g,src_b,dst_r,dst_g,dst_b"
crows = ["%g,%g,%g,%g,%g,%g" % (r / 4, g / 4, b / 4, r / 4 * 0.9, g / 4, b / 4 * 1.1)
         for r in range(3) for g in range(3) for b in range(3)]
put("c-ok.csv", "\n".join([CHEAD] + crows) + "\n")
put("c-nan.csv", "\n".join([CHEAD] + crows[:4] + ["nan,0,0,0,0,0"] + crows[4:]) + "\n")
put("c-1e300.csv", "\n".join([CHEAD] + crows[:4] + ["1e300,0,0,0,0,0"] + crows[4:]) + "\n")
put("c-srgb-huge.csv", "\n".join([CHEAD] + crows[:4] + ["1e308,0,0,0,0,0"] + crows[4:]) + "\n")
put("c-empty.csv", "")
put("c-two.csv", "\n".join([CHEAD] + crows[:2]) + "\n")
put("c-bad-row.csv", "\n".join([CHEAD] + crows[:4] + ["0,0,red,0,0,0"] + crows[4:]) + "\n")
put("c-same.csv", "\n".join([CHEAD] + [crows[3]] * 20) + "\n")

# --- point clouds -------------------------------------------------------------------------------
shutil.copy(os.path.join(resources, "cube.ply"), os.path.join(out, "cube.ply"))
ply_head = ("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nend_header\n")
put("ply-ok.ply", ply_head + "0 0 0\n1 0.5 -2\n0.25 0 3.5\n")
put("ply-truncated.ply", ply_head + "0 0 0\n1 0.5")
put("ply-lying-count.ply", ply_head.replace("vertex 3", "vertex 1000000000000") + "0 0 0\n")
put("ply-negative-count.ply", ply_head.replace("vertex 3", "vertex -5") + "0 0 0\n")
put("ply-nan.ply", ply_head + "0 0 0\nnan 0.5 -2\n0.25 0 3.5\n")
put("ply-zero.ply", ply_head.replace("vertex 3", "vertex 0"))
put("ply-no-end.ply", ply_head.replace("end_header\n", ""))
put("ply-unknown-format.ply", ply_head.replace("ascii", "binary_middle_endian"))
put("ply-no-xyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float q\nend_header\n1\n")
bin_head = ("ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\n"
            "property float y\nproperty float z\nend_header\n")
put("ply-binary-cut.ply", bin_head.encode() + struct.pack("<3f", 0, 0, 0) * 10)
put("ply-list-huge.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
    "property float y\nproperty float z\nelement face 1\nproperty list uint int vertex_indices\n"
    "end_header\n0 0 0\n4000000000 1 2 3\n")
put("ply-not.ply", "solid cube\nfacet normal 0 0 1\n")
put("ply-empty.ply", "")
put("ply-1e300.ply", ply_head + "0 0 0\n1e300 0.5 -2\n0.25 0 3.5\n")

# --- projects -----------------------------------------------------------------------------------


def project(photo="ok.png", **extra):
    d = {"format": "artcam-studio-project", "version": 2, "photo": photo, "model": "auto",
         "pairs": [], "camera": camera()}
    d.update(extra)
    return d


put_json("proj-ok.artcamproj", project())
put_json("proj-missing-photo.artcamproj", project("nowhere.png"))
put_json("proj-cut-photo.artcamproj", project("cut-half.png"))
put_json("proj-giant-photo.artcamproj", project("giant-padded.png"))
put_json("proj-photo-is-project.artcamproj", project("proj-ok.artcamproj"))
put_json("proj-photo-folder.artcamproj", project("folder.png"))
put_json("proj-zero-camera.artcamproj", project(camera=camera([[[0] * 3] * 3] * 3)))
put_json("proj-pole-camera.artcamproj", project(camera=camera(denominator(
    [[0, 0, 0.5], [0, 0, 0], [0.5, 0, 0]]))))
put_json("proj-camera-string.artcamproj", project(camera="identity.artcam"))
put("proj-nan-pair.artcamproj", json.dumps(project(pairs=[{"source": [1, 2], "target": [3, 4],
                                                           "enabled": True}]))
    .replace("[1, 2]", "[NaN, 2]"))
put_json("proj-model-unknown.artcamproj", project(model="wobbly"))
put_json("proj-version-99.artcamproj", project(version=99))
put("proj-bad-json.artcamproj", json.dumps(project())[:-3])
put("proj-empty.artcamproj", "")
put("proj-deep.artcamproj", "[" * 100000)
put_json("proj-giant-mask.artcamproj", project(depth={"layers": [{
    "name": "p", "size": [1 << 20, 1 << 20], "mask": "AAX/Aw==",
    "anchors": [{"pixel": [0.5, 0.5], "depth": 2}, {"pixel": [3.5, 0.5], "depth": 3},
                {"pixel": [0.5, 1.5], "depth": 4}]}]}))
put_json("proj-depth-cut.artcamproj", project(depth={"layers": [], "map": {
    "path": "depth-cut.tif", "scale": 1, "inverse": False}}))
put_json("proj-effect-unknown.artcamproj", project(effects=[{"name": "sparkle"}]))

# --- presets (written by artcam itself: valid files the hostile ones are compared with) ----------
for name, args in [("twist-3d.artcam", ["twist-3d"]),
                   ("aerial.artcam", ["aerial-perspective", "--size", "64x48"]),
                   ("photo-glc.artcam", ["photo-glc", "--size", "64x48"]),
                   ("barrel.artcam", ["barrel", "--size", "64x48"]),
                   ("over.artcam", ["composite", "--op", "over", "--size", "64x48"]),
                   ("pinhole.artcam", ["pinhole"])]:
    subprocess.run([artcam, "preset", *args, "-o", os.path.join(out, name)], check=True,
                   stdout=subprocess.DEVNULL)

# --- each area's own files ------------------------------------------------------------------------
_here = os.path.dirname(os.path.abspath(__file__))
for _name in sorted(os.listdir(_here)):
    if _name.startswith("files_") and _name.endswith(".py"):
        with open(os.path.join(_here, _name)) as _f:
            exec(compile(_f.read(), _name, "exec"))

# SPDX-License-Identifier: Apache-2.0
# Files for cases-bounds.tsv: inputs whose few bytes ask for unbounded memory or time (runs
# inside make_files.py, whose put/put_json/project/camera are in scope). Each stays small on
# disk except where the size is the point (the zero-filled "image", a few MB).
import base64 as _b64
import os as _os

# A run-length mask (region_mask.h: a value byte, then the run as a base-128 varint) of one run
# of n uncovered pixels: 8 characters of base64 for a 32768x32768 mask.
def _one_run(n):
    varint = bytearray()
    while True:
        varint.append((n & 0x7F) | (0x80 if n >= 0x80 else 0))
        n >>= 7
        if n == 0:
            break
    return _b64.b64encode(bytes([0]) + bytes(varint)).decode()


_side = 32768
_layer = {"name": "p", "size": [_side, _side], "mask": _one_run(_side * _side), "anchors": []}
# Twelve layers of 32768^2 masks: 12 GiB of masks from 1.6 KB of JSON.
put_json("bd-mask-bomb.artcamproj", project(depth={"layers": [_layer] * 12}))
# One such layer: within the 2^30-pixel limit of a mask, yet the photo it implies (float,
# with its depth raster) is beyond any budget the corpus runs with.
put_json("bd-mask-one.artcamproj", project(depth={"layers": [_layer]}))
# 20 000 effects in 1 MB: the stack's work must be linear in it.
put_json("bd-effects-20k.artcamproj", project(version=3, effects=[
    {"effect": "twist", "params": {"rate": [0.001]}}] * 20000))
# 200 000 lines of one point each (line,x,y): the label search must not be quadratic.
put("bd-lines-200k.csv", "line,x,y\n" + "".join("L%d,%d.5,%d.5\n" % (k, k % 64, k % 48)
                                                for k in range(200000)))
# 4 MB of zeros named .png: no format's magic, so no reader may crawl through it.
put("bd-zeros.png", bytes(4 << 20))
put("bd-zeros.artcam", bytes(1 << 20))
# A named pipe (nothing ever writes it: a reader that opened it would block forever).
_fifo = _os.path.join(out, "bd-fifo")
if not _os.path.exists(_fifo):
    _os.mkfifo(_fifo)
_os.makedirs(_os.path.join(out, "bd-folder.artcam"), exist_ok=True)

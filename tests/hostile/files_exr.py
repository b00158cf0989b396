# SPDX-License-Identifier: Apache-2.0
# Files for cases-exr.tsv (run by make_files.py with its helpers in scope: put, oiio, out):
# OpenEXR plates with chromaticities that make no RGB space, a valid ACEScg plate, an OpenColorIO
# config that is not one, a two-part file whose parts differ in size, and an overscan plate.
import OpenImageIO as _oiio
import numpy as _np


def _exr(name, specs, images):
    path = os.path.join(out, name)
    o = _oiio.ImageOutput.create(path)
    ok = o.open(path, tuple(specs)) if len(specs) > 1 else o.open(path, specs[0])
    for k, (spec, image) in enumerate(zip(specs, images)):
        if k:
            ok = ok and o.open(path, spec, "AppendSubimage")
        ok = ok and o.write_image(image)
    if not (ok and o.close()):
        raise SystemExit("cannot write " + name)


def _plate(chromaticities=None, w=64, h=48):
    spec = _oiio.ImageSpec(w, h, 3, "half")
    if chromaticities is not None:
        spec.attribute("chromaticities", _oiio.TypeDesc("float[8]"), tuple(chromaticities))
    return spec, _np.full((h, w, 3), 0.4, _np.float32)


for _name, _xy in [("ex-chroma-flat.exr", (0.3, 0.3) * 3 + (0.3127, 0.329)),
                   ("ex-chroma-zero-y.exr", (0.713, 0.0, 0.165, 0.83, 0.128, 0.044, 0.32168, 0.33767)),
                   ("ex-chroma-nan.exr", (float("nan"),) + (0.293, 0.165, 0.83, 0.128, 0.044, 0.32168, 0.33767)),
                   ("ex-acescg.exr", (0.713, 0.293, 0.165, 0.83, 0.128, 0.044, 0.32168, 0.33767))]:
    _s, _i = _plate(_xy)
    _exr(_name, [_s], [_i])
put("ex-garbage.ocio", b"ocio_profile_version: 2\ncolorspaces: [ {{{ not yaml\n")
_a, _ai = _plate()
_a.attribute("name", "beauty")
_b, _bi = _plate(w=32, h=24)
_b.attribute("name", "small")
_b.full_width, _b.full_height = 64, 48  # one display window for every part (OpenEXR's rule)
_exr("ex-two-size.exr", [_a, _b], [_ai, _bi])
_o, _oi = _plate(w=80, h=60)
_o.x, _o.y, _o.full_x, _o.full_y, _o.full_width, _o.full_height = -8, -6, 0, 0, 64, 48
_exr("ex-overscan.exr", [_o], [_oi])

# SPDX-License-Identifier: Apache-2.0
# Files for cases-fidelity.tsv (run by make_files.py with its helpers in scope: put, oiio,
# tiff_with_icc, icc_header, out). Channel layouts without alpha (a renderer's R,G,B,Z; normals;
# 200 channels; a five-sample TIFF) and ICC profiles that do not describe the pixels (grey, Lab,
# cut, noise, CMYK) on 8-bit files, which the stored-value path reads; profiles are made with
# lcms2 and the CMYK JPEG with TurboJPEG, both through ctypes, and embedded as an APP2 segment.
import ctypes as _ct
import struct as _st
import subprocess as _sp

oiio("fi-rgbz.exr", "--pattern", "constant:color=0.1,0.2,0.3,5", "64x48", "4",
     "--chnames", "R,G,B,Z", "-d", "half")
oiio("fi-rgbn.exr", "--pattern", "constant:color=0.1,0.2,0.3,0.1,0.2,0.9", "64x48", "6",
     "--chnames", "R,G,B,N.x,N.y,N.z", "-d", "half")
oiio("fi-200.exr", "--pattern", "constant:color=" + ",".join("%.2f" % (0.005 * k) for k in range(200)),
     "64x48", "200", "--chnames", ",".join(["R", "G", "B"] + ["aov%03d" % k for k in range(197)]),
     "-d", "half")
# Five 8-bit samples, none of them alpha (TIFF ExtraSamples "unspecified"; oiiotool would make
# the fourth one alpha).
import OpenImageIO as _oiio
_spec = _oiio.ImageSpec(64, 48, 5, "uint8")
_spec.alpha_channel = -1
_five = _oiio.ImageOutput.create(os.path.join(out, "fi-five.tif"))
if not (_five.open(os.path.join(out, "fi-five.tif"), _spec) and
        _five.write_image(bytes([30, 60, 90, 120, 200]) * (64 * 48)) and _five.close()):
    raise SystemExit("cannot write fi-five.tif")

_lcms = _ct.CDLL("liblcms2.so.2")
for _f, _res, _args in [("cmsBuildGamma", _ct.c_void_p, [_ct.c_void_p, _ct.c_double]),
                        ("cmsCreateGrayProfile", _ct.c_void_p, [_ct.c_void_p, _ct.c_void_p]),
                        ("cmsCreateLab4Profile", _ct.c_void_p, [_ct.c_void_p]),
                        ("cmsSaveProfileToMem", _ct.c_int,
                         [_ct.c_void_p, _ct.c_void_p, _ct.POINTER(_ct.c_uint32)])]:
    getattr(_lcms, _f).restype = _res
    getattr(_lcms, _f).argtypes = _args


def _saved(profile):
    size = _ct.c_uint32(0)
    _lcms.cmsSaveProfileToMem(profile, None, _ct.byref(size))
    data = _ct.create_string_buffer(size.value)
    _lcms.cmsSaveProfileToMem(profile, data, _ct.byref(size))
    return data.raw[:size.value]


_grey = _saved(_lcms.cmsCreateGrayProfile((_ct.c_double * 3)(0.3127, 0.3290, 1.0),
                                          _lcms.cmsBuildGamma(None, 2.2)))
_profiles = {"grey": _grey, "lab": _saved(_lcms.cmsCreateLab4Profile(None)),
             "cut": _grey[: len(_grey) // 2],
             "noise": b"acsp" + bytes((i * 37) % 256 for i in range(300)),
             "cmyk": icc_header(132, space=b"CMYK")}


def _with_icc(jpeg, icc):
    body = b"ICC_PROFILE\x00\x01\x01" + icc
    return jpeg[:2] + b"\xff\xe2" + _st.pack(">H", len(body) + 2) + body + jpeg[2:]


_ppm = b"P6\n64 48\n255\n" + bytes((x * 4 + c * 60) % 256 for y in range(48) for x in range(64)
                                   for c in range(3))
_rgb_jpeg = _sp.run(["cjpeg", "-quality", "90"], input=_ppm, stdout=_sp.PIPE, check=True).stdout
for _name, _icc in _profiles.items():
    put("fi-icc-%s.jpg" % _name, _with_icc(_rgb_jpeg, _icc))
    put("fi-icc-%s.tif" % _name, tiff_with_icc(_icc))

# A CMYK JPEG (Adobe-style, four components) carrying a CMYK profile: OpenImageIO's reader
# makes RGB of the inks without the profile.
_tj = _ct.CDLL("libturbojpeg.so.0")
_tj.tjInitCompress.restype = _ct.c_void_p
_tj.tjCompress2.argtypes = [_ct.c_void_p, _ct.c_char_p, _ct.c_int, _ct.c_int, _ct.c_int, _ct.c_int,
                            _ct.POINTER(_ct.c_void_p), _ct.POINTER(_ct.c_ulong), _ct.c_int,
                            _ct.c_int, _ct.c_int]
_inks = bytes((x * 4 + c * 50) % 256 for y in range(48) for x in range(64) for c in range(4))
_buf, _size = _ct.c_void_p(None), _ct.c_ulong(0)
_TJPF_CMYK, _TJSAMP_444 = 11, 0
if _tj.tjCompress2(_tj.tjInitCompress(), _inks, 64, 0, 48, _TJPF_CMYK, _ct.byref(_buf),
                   _ct.byref(_size), _TJSAMP_444, 90, 0) != 0:
    raise SystemExit("TurboJPEG could not make the CMYK JPEG")
put("fi-cmyk.jpg", _with_icc(_ct.string_at(_buf, _size.value), _profiles["cmyk"]))

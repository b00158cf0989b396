# SPDX-License-Identifier: Apache-2.0
# Files for cases-lensexif.tsv (run by make_files.py with its helpers in scope: out, ...):
# JPEGs whose EXIF names a camera and lens as a photo would, but with values no lens camera can
# be made from: a focal length of zero, negative, enormous or not a number; a 60 000-character
# lens name; a lens name and camera lensfun does not know. Written by OpenImageIO, which puts
# the tags where a camera does (Make/Model in IFD0, FocalLength in the Exif IFD).
import OpenImageIO as _oiio


def _exif_jpeg(name, **tags):
    spec = _oiio.ImageSpec(64, 48, 3, "uint8")
    for key, value in tags.items():
        spec.attribute({"make": "Make", "model": "Model", "lens": "Exif:LensModel",
                        "focal": "Exif:FocalLength"}[key], value)
    path = os.path.join(out, name)
    image = _oiio.ImageOutput.create(path)
    if not (image.open(path, spec) and image.write_image(bytes([90, 120, 150]) * (64 * 48)) and
            image.close()):
        raise SystemExit("cannot write " + name)


_g11 = {"make": "Canon", "model": "Canon PowerShot G11"}
_exif_jpeg("le-focal-zero.jpg", focal=0.0, lens="6.1-30.5 mm", **_g11)
_exif_jpeg("le-focal-negative.jpg", focal=-6.1, lens="6.1-30.5 mm", **_g11)
_exif_jpeg("le-focal-huge.jpg", focal=3.0e38, lens="6.1-30.5 mm", **_g11)
_exif_jpeg("le-focal-nan.jpg", focal=float("nan"), lens="6.1-30.5 mm", **_g11)
_exif_jpeg("le-lens-long.jpg", focal=6.1, lens="x" * 60000, **_g11)
_exif_jpeg("le-unknown.jpg", focal=50.0, make="Acme", model="Acme Zorp 9", lens="Zorpinar 50mm")
_exif_jpeg("le-no-lens.jpg", focal=50.0)

# SPDX-License-Identifier: Apache-2.0
"""ARTcam for Python: Attributed Rational Tensor cameras over numpy arrays.

Every output coordinate of an ARTcam (position, colour, depth) is a ratio of quadratic forms of
the input point; one camera value covers homographies, push-broom and crossed-slits cameras,
rational lens distortion, chromatic aberration and colour effects. This module is the engine of
the ``artcam`` command line, not a wrapper around it: the same reader, writer and renderer, the
same pixels, and refusals raised as ValueError / OSError carrying the CLI's messages.

    import artcam
    cam = artcam.read("lens.artcam")
    photo = artcam.read_image("photo.jpg")
    out = cam.warp(photo.pixels)                # no copy of the input; the GIL is released
    artcam.write_image("fixed.jpg", out, like=photo)

``artcam.dask`` runs a frame sequence over a ``distributed.Client``.
"""
from ._artcam import *  # noqa: F401,F403
from ._artcam import Camera, Image, read, from_json, read_image, write_image  # noqa: F401

__version__ = "0.1.0"


def warp(camera, image, **options):
    """``camera.warp(image, **options)``: renders `image` through `camera` (an artcam.Camera, or
    a .artcam path), as ``artcam warp`` renders a photo. See help(artcam.Camera.warp)."""
    if not isinstance(camera, Camera):
        camera = read(str(camera))
    return camera.warp(image, **options)


warp.__doc__ += "\n\n" + (Camera.warp.__doc__ or "")

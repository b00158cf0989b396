# SPDX-License-Identifier: Apache-2.0
# artcam.export_map against `artcam export-map` and OpenCV's remap; artcam.export_project against
# `artcam export` byte for byte.
import json
import shutil

import numpy as np
import pytest

import artcam
from conftest import gradient_photo

import cv2  # python3-opencv and python3-openimageio (install-deps.sh): outside truths
import OpenImageIO as oiio


def read_exr(path):
    """Every channel of an EXR as OpenImageIO reads it (not through artcam's reader)."""
    file = oiio.ImageInput.open(str(path))
    pixels = file.read_image(format="float")
    file.close()
    return pixels


def test_export_map_is_the_cli_file(run_cli, tmp_path):
    camera = artcam.preset("barrel", k=-0.2, size=(600, 400))
    camera.write(str(tmp_path / "b.artcam"))
    for convention, channels in (("stmap", 4), ("opencv", 2)):
        m = artcam.export_map(camera, (300, 200), convention=convention,
                              path=tmp_path / f"py-{convention}.exr")
        assert m.shape == (200, 300, channels) and m.dtype == np.float32
        run_cli("export-map", tmp_path / "b.artcam", "--size", "300x200", "--convention",
                convention, "-o", tmp_path / f"cli-{convention}.exr")
        cli = read_exr(tmp_path / f"cli-{convention}.exr")
        assert np.array_equal(cli, read_exr(tmp_path / f"py-{convention}.exr"))
        assert np.array_equal(cli, m)
    # A per-channel camera: one map per colour channel, side by side.
    ca = artcam.preset("chromatic-aberration", size=(600, 400))
    assert artcam.export_map(ca, (60, 40)).shape == (40, 60, 12)
    with pytest.raises(ValueError, match="stmap or opencv"):
        artcam.export_map(camera, (300, 200), convention="uv")


def test_opencv_map_warps_as_the_camera(tmp_path):
    camera = artcam.preset("barrel", k=-0.2, size=(160, 120))
    photo = gradient_photo(160, 120)
    m = artcam.export_map(camera, (160, 120), convention="opencv")
    remapped = cv2.remap(photo, m[..., 0], m[..., 1], cv2.INTER_LINEAR,
                         borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    warped = camera.warp(photo)
    inside = m[..., 0] > 2
    inside &= (m[..., 0] < 157) & (m[..., 1] > 2) & (m[..., 1] < 117)
    diff = np.abs(remapped.astype(int) - warped.astype(int))[inside]
    assert inside.sum() > 10000 and diff.max() <= 2  # OpenCV's 5-bit bilinear weights


def test_export_project_equals_the_cli(run_cli, samples, tmp_path):
    for name in ("sample.artcamproj", "coffee.png"):
        shutil.copy(samples / name, tmp_path / name)
    project = tmp_path / "sample.artcamproj"
    report = artcam.export_project(str(project), str(tmp_path / "py.png"),
                                   camera_out=str(tmp_path / "py.artcam"))
    cli = json.loads(run_cli("export", project, "-o", tmp_path / "cli.png", "--camera-out",
                             tmp_path / "cli.artcam", "--json").stdout)
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()
    assert (tmp_path / "py.artcam").read_text() == (tmp_path / "cli.artcam").read_text()
    assert (report["width"], report["height"]) == (cli["width"], cli["height"])
    assert report["camera"].to_json() == (tmp_path / "cli.artcam").read_text()
    half = artcam.export_project(str(project), str(tmp_path / "half.jpg"), size=(300, 0),
                                 quality=90)
    assert half["width"] == 300 and half["kind"] == cli["camera"]
    # A colour as a sequence reaches the CLI's parser as its list (this project leaves no pixel
    # without a preimage, so the range check is what shows it).
    artcam.export_project(str(project), str(tmp_path / "fill.png"), fill=(0.2, 0.4, 0.6))
    with pytest.raises(ValueError, match="--fill expects 3 or 4 comma-separated numbers"):
        artcam.export_project(str(project), str(tmp_path / "fill2.png"), fill=(2, 0, 0))
    with pytest.raises(OSError, match="exists; pass --overwrite"):
        artcam.export_project(str(project), str(tmp_path / "py.png"))
    with pytest.raises(FileNotFoundError):
        artcam.export_project(str(tmp_path / "none.artcamproj"), str(tmp_path / "n.png"))
    with pytest.raises(ValueError, match="--quality"):
        artcam.export_project(str(project), str(tmp_path / "q.jpg"), quality=0)
    with pytest.raises(TypeError, match="unexpected keyword"):
        artcam.export_project(str(project), str(tmp_path / "q.jpg"), sharpen=1)

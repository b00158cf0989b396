# SPDX-License-Identifier: Apache-2.0
import numpy as np
import pytest

import artcam
from conftest import gradient_photo


def test_warp_of_an_array_equals_the_cli_warp_of_its_file(samples, run_cli, tmp_path):
    photo = gradient_photo(600, 400)
    artcam.write_image(str(tmp_path / "in.png"), photo)
    run_cli("warp", tmp_path / "in.png", samples / "sample.artcam", "-o", tmp_path / "cli.tif",
            "--edge", "black")
    cli = artcam.read_image(str(tmp_path / "cli.tif")).pixels
    cam = artcam.read(str(samples / "sample.artcam"))
    out = cam.warp(photo, edge="black")
    assert out.dtype == np.uint8 and out.shape == cli.shape
    np.testing.assert_array_equal(out, cli)


def test_write_image_like_keeps_bytes_of_the_cli_path(samples, run_cli, tmp_path):
    photo = artcam.read_image(str(samples / "coffee.png"))
    cam = artcam.read(str(samples / "sample.artcam"))
    artcam.write_image(str(tmp_path / "py.png"), cam.warp(photo.pixels), like=photo)
    run_cli("warp", samples / "coffee.png", samples / "sample.artcam", "-o", tmp_path / "cli.png")
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()


@pytest.mark.parametrize("dtype", [np.uint8, np.uint16, np.float32])
def test_warp_keeps_dtype_and_reads_strided_rows(samples, dtype):
    cam = artcam.read(str(samples / "sample.artcam"))
    big = gradient_photo(700, 500, dtype=dtype)
    crop = big[50:450, 60:660]  # rows strided, pixels packed: read in place
    assert not crop.flags.c_contiguous
    out = cam.warp(crop, edge="black")
    assert out.dtype == dtype
    np.testing.assert_array_equal(out, cam.warp(np.ascontiguousarray(crop), edge="black"))


def test_alpha_marks_pixels_without_a_preimage(run_cli, tmp_path):
    run_cli("preset", "barrel", "--k", "-0.3", "--size", "600x400", "-o", tmp_path / "b.artcam")
    cam = artcam.read(str(tmp_path / "b.artcam"))
    out = cam.warp(gradient_photo(600, 400), alpha=True)
    assert out.shape[2] == 4
    transparent = out[..., 3] == 0
    assert transparent.any() and not transparent.all()
    assert (out[transparent][:, :3] == 0).all()  # premultiplied


def test_refusals(samples, tmp_path):
    cam = artcam.read(str(samples / "sample.artcam"))
    photo = gradient_photo(600, 400)
    with pytest.raises(ValueError, match="dtype float64"):
        cam.warp(photo.astype(np.float64))
    with pytest.raises(ValueError, match="not contiguous"):
        cam.warp(photo[:, ::2])
    with pytest.raises(ValueError, match="channels"):
        cam.warp(np.zeros((10, 10, 5), np.uint8))
    with pytest.raises(ValueError, match="filter"):
        cam.warp(photo, filter="lanczos")
    with pytest.raises(FileNotFoundError, match="missing.png"):
        artcam.read_image(str(tmp_path / "missing.png"))
    with pytest.raises(ValueError, match="--quality"):
        artcam.write_image(str(tmp_path / "q.jpg"), photo, quality=500)
    assert not (tmp_path / "q.jpg").exists()
    with pytest.raises(OSError, match="no-such-folder"):
        artcam.write_image(str(tmp_path / "no-such-folder" / "x.png"), photo)


def test_aspect_stretch_is_warned(samples):
    cam = artcam.read(str(samples / "sample.artcam"))
    with pytest.warns(UserWarning, match="aspect|stretch"):
        cam.warp(gradient_photo(400, 400))


def test_out_renders_into_the_callers_array(samples):
    cam = artcam.read(str(samples / "sample.artcam"))
    photo = gradient_photo(600, 400)
    expected = cam.warp(photo)
    into = np.zeros_like(expected)
    assert cam.warp(photo, out=into) is into
    np.testing.assert_array_equal(into, expected)
    with pytest.raises(ValueError, match="out: expected a 400×600×3"):
        cam.warp(photo, out=np.zeros((400, 600, 4), np.uint8))
    frozen = np.zeros_like(expected)
    frozen.flags.writeable = False
    with pytest.raises(ValueError, match="read-only"):
        cam.warp(photo, out=frozen)


def test_warp_holds_no_copy_of_a_24_megapixel_photo(run_cli, tmp_path):
    # In a fresh process: the peak RSS growth from before the input exists to after the warp is
    # input + output + 64 MiB at most (a float copy of the input alone would be 288 MB more).
    import subprocess
    import sys
    run_cli("preset", "lens-distortion", "--k1", "-0.1", "--size", "6000x4000", "-o",
            tmp_path / "lens.artcam")
    bench = __import__("pathlib").Path(__file__).parents[1] / "bench" / "warp_array.py"
    code = (
        "import sys; sys.path.insert(0, %r)\n"
        "import warp_array, artcam\n"
        "cam = artcam.read(%r)\n"
        "before = warp_array.peak_rss_bytes()\n"
        "photo = warp_array.make_photo(6000, 4000)\n"
        "out = cam.warp(photo)\n"
        "print(warp_array.peak_rss_bytes() - before, photo.nbytes + out.nbytes)\n"
    ) % (str(bench.parent), str(tmp_path / "lens.artcam"))
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    grown, images = map(int, done.stdout.split())
    assert images == 2 * 6000 * 4000 * 3
    assert grown <= images + (64 << 20), f"peak grew {grown >> 20} MiB for {images >> 20} MiB of images"


def test_the_gil_is_released_while_it_renders(run_cli, tmp_path):
    # Python keeps running beside a render on another thread: with the GIL held through the
    # render, the loop below would stand still until it ended.
    import threading
    import time
    run_cli("preset", "lens-distortion", "--k1", "-0.1", "--size", "3000x2000", "-o",
            tmp_path / "lens.artcam")
    cam = artcam.read(str(tmp_path / "lens.artcam"))
    photo = gradient_photo(3000, 2000)
    spans = []

    def render():
        for _ in range(4):
            t = time.perf_counter()
            cam.warp(photo, filter="bicubic", threads=1)
            spans.append(time.perf_counter() - t)

    worker = threading.Thread(target=render)
    beats = []
    worker.start()
    while worker.is_alive():
        beats.append(time.perf_counter())
    worker.join()
    # The longest stretch without a beat of the loop is far shorter than one render.
    longest_gap = max(b - a for a, b in zip(beats, beats[1:]))
    assert longest_gap < 0.5 * min(spans), (longest_gap, spans)


def test_module_warp_and_frames(samples):
    cam = artcam.read(str(samples / "sample.artcam"))
    photo = gradient_photo(600, 400)
    np.testing.assert_array_equal(artcam.warp(str(samples / "sample.artcam"), photo), cam.warp(photo))
    assert cam.frames == {"source": cam.source_size, "target": cam.target_size}
    assert "filter" in artcam.warp.__doc__ and "no copy" in artcam.Camera.warp.__doc__


def test_finish_equals_the_cli(samples, run_cli, tmp_path):
    photo = artcam.read_image(str(samples / "coffee.png"))
    cam = artcam.read(str(samples / "sample.artcam"))
    assert "pencil" in [name for name, _ in artcam.finishes()]
    artcam.write_image(str(tmp_path / "py.png"), cam.warp(photo.pixels, finish="pencil"), like=photo)
    run_cli("warp", samples / "coffee.png", samples / "sample.artcam", "-o", tmp_path / "cli.png",
            "--finish", "pencil")
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()
    with pytest.raises(ValueError, match="unknown finish"):
        cam.warp(photo.pixels, finish="crayola")

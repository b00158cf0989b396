# SPDX-License-Identifier: Apache-2.0
# artcam.dask on a LocalCluster of two worker processes, against `artcam batch` byte for byte.
import os

import numpy as np
import pytest

import artcam
import artcam.dask
from conftest import gradient_photo

import distributed  # python3-distributed (install-deps.sh): a missing peer fails, not skips


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    with cluster, distributed.Client(cluster) as c:
        yield c


def make_sequence(folder, count=6, first=1001):
    folder.mkdir()
    for k in range(count):
        photo = np.roll(gradient_photo(240, 160), 9 * k, axis=1)
        artcam.write_image(str(folder / f"f_{first + k:04d}.jpg"), photo, quality=90)
    return str(folder / "f_%04d.jpg")


def test_sequence_on_two_workers_equals_batch(client, run_cli, samples, tmp_path):
    pattern = make_sequence(tmp_path / "plates")
    cam = samples / "sample.artcam"
    run_cli("batch", cam, pattern, "-o", tmp_path / "batch", "--filter", "bicubic", "--first", 1001, "--quiet")
    result = artcam.dask.warp_sequence(client, str(cam), pattern, tmp_path / "dask",
                                       first=1001, filter="bicubic")
    assert result.failed == [] and len(result.done) == 6
    # Both workers took part: the frames were spread, not run on one.
    assert len({row["worker"] for row in result.rows}) == 2
    names = sorted(os.listdir(tmp_path / "batch"))
    assert names == sorted(os.listdir(tmp_path / "dask")) and len(names) == 6
    for name in names:
        assert (tmp_path / "batch" / name).read_bytes() == (tmp_path / "dask" / name).read_bytes()
    assert "6 written, 0 skipped, 0 failed" in result.table()


def test_chunks_of_frames_and_a_failed_frame(client, samples, tmp_path):
    pattern = make_sequence(tmp_path / "plates", count=5)
    (tmp_path / "plates" / "f_1003.jpg").write_bytes(b"not a jpeg")
    result = artcam.dask.warp_sequence(client, artcam.read(str(samples / "sample.artcam")),
                                       pattern, tmp_path / "out", first=1001, chunk_size=2)
    assert len(result.done) == 4 and len(result.failed) == 1
    bad = [r for r in result.rows if r["status"] == "failed"][0]
    assert "f_1003.jpg" in bad["error"]
    assert not (tmp_path / "out" / "f_1003.jpg").exists()  # nothing half-written


def test_existing_outputs_refused_or_skipped(client, samples, tmp_path):
    pattern = make_sequence(tmp_path / "plates", count=3)
    cam = str(samples / "sample.artcam")
    artcam.dask.warp_sequence(client, cam, pattern, tmp_path / "out", first=1001)
    kept = (tmp_path / "out" / "f_1002.jpg").stat().st_mtime_ns
    with pytest.raises(OSError, match="exists; pass --overwrite"):
        artcam.dask.warp_sequence(client, cam, pattern, tmp_path / "out", first=1001)
    (tmp_path / "out" / "f_1003.jpg").unlink()
    again = artcam.dask.warp_sequence(client, cam, pattern, tmp_path / "out", first=1001,
                                      skip_existing=True)
    assert len(again.skipped) == 2 and len(again.done) == 1
    assert (tmp_path / "out" / "f_1002.jpg").stat().st_mtime_ns == kept
    with pytest.raises(ValueError, match="--quality"):
        artcam.dask.warp_sequence(client, cam, pattern, tmp_path / "q", first=1001,
                                   quality=0)


def test_frames_and_chunk_are_batchs(client, run_cli, samples, tmp_path):
    pattern = make_sequence(tmp_path / "plates", count=6)
    cam = str(samples / "sample.artcam")
    batch = run_cli("batch", cam, pattern, "-o", tmp_path / "batch", "--frames", "1001-1006x2",
                    "--chunk", "2/2", "--json")
    import json
    wanted = json.loads(batch.stdout)["frames"]["done"]
    result = artcam.dask.warp_sequence(client, cam, pattern, tmp_path / "dask",
                                       frames="1001-1006x2", chunk="2/2")
    assert sorted(result.done) == wanted == [1003, 1005]
    assert sorted(os.listdir(tmp_path / "dask")) == sorted(os.listdir(tmp_path / "batch"))
    for name in os.listdir(tmp_path / "batch"):
        assert (tmp_path / "batch" / name).read_bytes() == (tmp_path / "dask" / name).read_bytes()

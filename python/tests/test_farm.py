# SPDX-License-Identifier: Apache-2.0
# A render farm's split of one shot: four `artcam batch --chunk K/4` processes at once against
# one whole run, byte for byte; artcam.plan's frames and chunks are batch's.
import json
import os
import subprocess

import numpy as np
import pytest

import artcam
import artcam.dask
from conftest import gradient_photo


def make_shot(folder, first=1001, count=11):
    folder.mkdir()
    for k in range(count):
        photo = np.roll(gradient_photo(200, 130), 7 * k, axis=0)
        artcam.write_image(str(folder / f"plate.{first + k:04d}.png"), photo)
    return str(folder / "plate.%04d.png")


def test_four_chunks_equal_one_whole_run(cli, run_cli, samples, tmp_path):
    pattern = make_shot(tmp_path / "plates")
    cam = samples / "sample.artcam"
    whole = json.loads(run_cli("batch", cam, pattern, "-o", tmp_path / "whole",
                               "--frames", "1001-1011", "--json").stdout)
    assert whole["frames"]["done"] == list(range(1001, 1012))
    tasks = [subprocess.Popen([cli, "batch", str(cam), pattern, "-o", str(tmp_path / "farm"),
                               "--frames", "1001-1011", "--chunk", f"{k}/4", "--json",
                               "--threads", "1"],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for k in range(1, 5)]
    done = []
    for k, task in enumerate(tasks, start=1):
        out, err = task.communicate(timeout=120)
        assert task.returncode == 0, err
        report = json.loads(out)
        assert report["chunk"] == {"index": k, "count": 4}
        done += report["frames"]["done"]
        # The module plans the same slice.
        planned = artcam.dask.plan([pattern], tmp_path / "farm", frames="1001-1011", chunk=f"{k}/4")
        assert [frame for frame, _, _ in planned] == report["frames"]["done"]
        assert [o for _, _, o in planned] == [f["output"] for f in report["files"]]
    assert done == list(range(1001, 1012))  # every frame, once, in order
    names = sorted(os.listdir(tmp_path / "whole"))
    assert names == sorted(os.listdir(tmp_path / "farm")) and len(names) == 11
    for name in names:
        assert (tmp_path / "whole" / name).read_bytes() == (tmp_path / "farm" / name).read_bytes()


def test_plan_frames_steps_and_refusals(tmp_path):
    pattern = make_shot(tmp_path / "plates", count=3)
    planned = artcam.dask.plan([pattern], tmp_path / "out", frames="1001-1005x2")
    assert [f for f, _, _ in planned] == [1001, 1003, 1005]  # 1005 has no file: batch fails it
    assert planned[0][2].endswith("plate.1001.png")
    assert [f for f, _, _ in artcam.dask.plan([pattern], tmp_path / "out", first=1001)] == [1001, 1002,
                                                                                        1003]
    for kwargs, words in [({"frames": "1005-1001"}, "runs backwards"),
                          ({"frames": "abc"}, "frames \"abc\""),
                          ({"chunk": "5/4", "first": 1001}, "K/N"),
                          ({"frames": "1-2", "first": 1}, "give one")]:
        with pytest.raises(ValueError, match=words):
            artcam.dask.plan([pattern], tmp_path / "out", **kwargs)

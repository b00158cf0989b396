# SPDX-License-Identifier: Apache-2.0
import json
import pickle

import numpy as np
import pytest

import artcam


def test_read_gives_the_files_properties(samples):
    cam = artcam.read(str(samples / "sample.artcam"))
    doc = json.loads((samples / "sample.artcam").read_text())
    assert cam.kind == "single"
    assert cam.layers == 1 and cam.patches == 0
    assert list(cam.source_size) == doc["frames"]["source"]
    assert list(cam.target_size) == doc["frames"]["target"]


def test_map_equals_the_cli(samples, run_cli, tmp_path):
    points = np.array([[0.0, 0.0], [123.25, 77.5], [599.0, 399.0]])
    np.savetxt(tmp_path / "p.csv", points, delimiter=",", fmt="%.17g")
    out = run_cli("map", samples / "sample.artcam", tmp_path / "p.csv").stdout
    expected = np.array([[float(v) for v in row.split(",")[2:]] for row in out.split()])
    got = artcam.read(str(samples / "sample.artcam")).map(points)
    assert got.shape == (3, 2)
    np.testing.assert_array_equal(got, expected)  # %.17g round-trips exactly


def test_write_and_pickle_round_trip(samples, tmp_path):
    cam = artcam.read(str(samples / "sample.artcam"))
    cam.write(str(tmp_path / "again.artcam"))
    again = artcam.read(str(tmp_path / "again.artcam"))
    assert again.to_json() == cam.to_json()
    shipped = pickle.loads(pickle.dumps(cam))
    assert shipped.to_json() == cam.to_json()
    assert json.loads(cam.to_json())["frames"]["source"] == list(cam.source_size)


def test_refusals_carry_the_cli_messages(tmp_path, run_cli):
    missing = tmp_path / "missing.artcam"
    with pytest.raises(FileNotFoundError) as e:
        artcam.read(str(missing))
    cli = run_cli("info", missing, check=False)
    assert cli.returncode != 0
    assert str(e.value) in cli.stderr
    broken = tmp_path / "broken.artcam"
    broken.write_text('{"version": 1, "source_size": [10, 10]')
    with pytest.raises(ValueError) as e:
        artcam.read(str(broken))
    assert str(broken) in str(e.value)
    assert str(e.value) in run_cli("info", broken, check=False).stderr
    with pytest.raises(IsADirectoryError, match="a folder"):
        artcam.read(str(tmp_path))

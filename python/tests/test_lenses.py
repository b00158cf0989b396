# SPDX-License-Identifier: Apache-2.0
# artcam.lens_search and artcam.lens_camera against `artcam lens search` and `artcam lens camera`.
import json

import pytest

import artcam

LENS = "Canon PowerShot G11 & compatibles (Standard)"


def test_search_equals_the_cli(run_cli):
    found = artcam.lens_search("nikon 50mm 1.4", limit=0)
    cli = json.loads(run_cli("lens", "search", "nikon", "50mm", "1.4", "--limit", "0",
                             "--json").stdout)
    assert [{k: v for k, v in l.items() if k != "match"} for l in found] == cli["lenses"]
    assert found and all(l["match"] == cli["match"] for l in found)
    assert len(artcam.lens_search("nikon", limit=3)) == 3
    none = json.loads(run_cli("lens", "search", "xyzzy", "--limit", "0", "--json").stdout)
    assert len(artcam.lens_search("xyzzy", limit=0)) == none["found"]


def test_lens_camera_equals_the_cli(run_cli, tmp_path):
    camera, report = artcam.lens_camera(LENS, 6.1, (600, 400))
    cli = json.loads(run_cli("lens", "camera", "--lens", LENS, "--focal", "6.1", "--size",
                             "600x400", "--json", "-o", tmp_path / "g11.artcam").stdout)
    assert camera.to_json() == (tmp_path / "g11.artcam").read_text()
    assert {k: v for k, v in report.items() if k != "report"} == \
        {k: v for k, v in cli.items() if k != "output"}
    assert report["within_tolerance"]
    assert camera.frame == "sensor"
    with pytest.raises(ValueError, match="missing focal"):
        artcam.lens_camera(LENS, size=(600, 400))
    with pytest.raises(ValueError, match="photo gives them"):
        artcam.lens_camera(LENS, 6.1, (600, 400), photo="x.jpg")
    with pytest.raises(FileNotFoundError):
        artcam.lens_camera(photo=str(tmp_path / "missing.jpg"))
    cli_bad = run_cli("lens", "camera", "--lens", "No Such Lens 99", "--focal", "50", "--size",
                      "600x400", "-o", tmp_path / "bad.artcam", check=False)
    with pytest.raises(ValueError) as refused:
        artcam.lens_camera("No Such Lens 99", 50, (600, 400))
    assert str(refused.value) in cli_bad.stderr

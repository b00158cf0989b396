# SPDX-License-Identifier: Apache-2.0
# artcam.fit, fit_lines, fit_stmap and fit_colour against `artcam fit` on the same data written
# as files: the same camera text and the same report; refusals with the CLI's messages.
import json

import numpy as np
import pytest

import artcam


def write_pairs(path, header, a, b):
    rows = [",".join(f"{v:.17g}" for v in np.concatenate([x, y])) for x, y in zip(a, b)]
    path.write_text(header + "\n" + "\n".join(rows) + "\n")


def grid(n=6, width=600, height=400):
    xs, ys = np.meshgrid(np.linspace(30, width - 30, n), np.linspace(30, height - 30, n))
    return np.stack([xs.ravel(), ys.ravel()], axis=1)


def same_report(py, cli):
    """The module's report is the CLI's --json, plus the CLI's summary line."""
    return ({k: v for k, v in py.items() if k != "report"}
            == {k: v for k, v in cli.items() if k != "output"})


def test_fit_arrays_equal_fit_of_the_csv(run_cli, tmp_path):
    truth = artcam.preset("barrel", k=-0.1, size=(600, 400))
    src = grid()
    dst = truth.map(src) + np.random.default_rng(7).normal(0, 0.2, src.shape)
    camera, report = artcam.fit(src, dst, (600, 400), model="homography")
    write_pairs(tmp_path / "m.csv", "src_x,src_y,dst_x,dst_y", src, dst)
    cli = json.loads(run_cli("fit", tmp_path / "m.csv", "--size", "600x400", "--model",
                             "homography", "--json", "-o", tmp_path / "m.artcam").stdout)
    assert camera.to_json() == (tmp_path / "m.artcam").read_text()
    assert same_report(report, cli)
    assert report["report"].startswith("homography")
    # A path works as the CSV does; auto picks as the CLI picks.
    auto, auto_report = artcam.fit(str(tmp_path / "m.csv"), size=(600, 400))
    cli_auto = json.loads(run_cli("fit", tmp_path / "m.csv", "--size", "600x400", "--json",
                                  "-o", tmp_path / "auto.artcam").stdout)
    assert auto_report["model"] == cli_auto["model"]
    assert auto.to_json() == (tmp_path / "auto.artcam").read_text()
    # Robust: the outlier is left out, as the CLI leaves it.
    bad = dst.copy()
    bad[3] += 80
    robust, robust_report = artcam.fit(src, bad, (600, 400), model="homography", robust=True)
    assert 3 not in robust_report["inliers"]


def test_fit_refusals(run_cli, tmp_path):
    src = grid(2)
    with pytest.raises(ValueError, match="homography"):
        artcam.fit(src[:3], src[:3] + 1, (600, 400), model="homography")
    nan = grid()
    nan[2, 0] = np.nan
    with pytest.raises(ValueError, match="<matches>:4"):
        artcam.fit(nan, grid(), (600, 400))
    with pytest.raises(ValueError, match="N×2"):
        artcam.fit(np.zeros((5, 4)), np.zeros((5, 4)), (600, 400))
    with pytest.raises(ValueError, match="sources but"):
        artcam.fit(grid(), grid()[:5], (600, 400))
    with pytest.raises(ValueError, match="unknown model"):
        artcam.fit(grid(), grid(), (600, 400), model="spline")
    with pytest.raises(FileNotFoundError, match="missing.csv"):
        artcam.fit(str(tmp_path / "missing.csv"), size=(600, 400))
    with pytest.raises(ValueError, match="size"):
        artcam.fit(grid(), grid())


def bent_lines(camera, count=5):
    """Straight lines of the target frame traced through the camera's inverse: a barrel photo's
    edges (the camera maps them straight)."""
    lines = []
    inverse = artcam.preset("pincushion", k=0.1, size=(600, 400))
    for k in range(count):
        t = np.linspace(40, 560, 12)
        horizontal = np.stack([t, np.full_like(t, 40 + 80 * k)], axis=1)
        lines.append(inverse.map(horizontal))
        vertical = np.stack([np.full_like(t[:8], 60 + 120 * k), np.linspace(40, 360, 8)], axis=1)
        lines.append(inverse.map(vertical))
    return lines


def test_fit_lines_equals_the_cli(run_cli, tmp_path):
    lines = bent_lines(None)
    camera, report = artcam.fit_lines(lines, (600, 400))
    rows = [f"{k + 1},{x:.17g},{y:.17g}" for k, line in enumerate(lines) for x, y in line]
    (tmp_path / "lines.csv").write_text("line,x,y\n" + "\n".join(rows) + "\n")
    cli = json.loads(run_cli("fit", "--lines", tmp_path / "lines.csv", "--size", "600x400",
                             "--json", "-o", tmp_path / "lines.artcam").stdout)
    assert camera.to_json() == (tmp_path / "lines.artcam").read_text()
    assert same_report(report, cli)
    # Straighter than the photo's lines were (the middle ones are straight in both).
    assert report["max_bow_px"] < 0.2 * max(l["bow_before_px"] for l in report["lines"])
    by_path, _ = artcam.fit_lines(tmp_path / "lines.csv", (600, 400))
    assert by_path.to_json() == camera.to_json()
    labelled, _ = artcam.fit_lines({str(k + 1): line for k, line in enumerate(lines)}, (600, 400))
    assert labelled.to_json() == camera.to_json()
    with pytest.raises(ValueError, match="radial or quadratic"):
        artcam.fit_lines(lines, (600, 400), model="homography")
    with pytest.raises(ValueError, match="line 1"):
        artcam.fit_lines([np.zeros((4, 3))], (600, 400))


def test_fit_stmap_equals_the_cli(run_cli, tmp_path):
    truth = artcam.preset("barrel", k=-0.15, size=(600, 400))
    artcam.export_map(truth, (600, 400), path=tmp_path / "map.exr")
    camera, report = artcam.fit_stmap(str(tmp_path / "map.exr"))
    cli = json.loads(run_cli("fit", "--stmap", tmp_path / "map.exr", "--json", "-o",
                             tmp_path / "map.artcam").stdout)
    assert camera.to_json() == (tmp_path / "map.artcam").read_text()
    assert report["rms_px"] == cli["rms_px"] and report["samples"] > 100
    with pytest.raises(FileNotFoundError):
        artcam.fit_stmap(str(tmp_path / "nothing.exr"))


def test_fit_colour_equals_the_cli(run_cli, tmp_path):
    rng = np.random.default_rng(3)
    src = rng.uniform(0.05, 0.95, (24, 3))
    matrix = np.array([[0.9, 0.1, 0.0], [0.05, 0.85, 0.1], [0.0, 0.1, 0.95]])
    dst = src @ matrix.T + 0.02
    camera, report = artcam.fit_colour(src, dst, (600, 400))
    write_pairs(tmp_path / "c.csv", "src_r,src_g,src_b,dst_r,dst_g,dst_b", src, dst)
    cli = json.loads(run_cli("fit", tmp_path / "c.csv", "--block", "colour", "--size",
                             "600x400", "--json", "-o", tmp_path / "c.artcam").stdout)
    assert camera.to_json() == (tmp_path / "c.artcam").read_text()
    assert same_report(report, cli) and report["candidates"]
    assert report["max_de"] < 0.5  # an affine map, recovered
    with pytest.raises(ValueError, match="root-polynomial"):
        artcam.fit_colour(src, dst, (600, 400), model="root-polynomial")
    with pytest.raises(ValueError, match="N×3"):
        artcam.fit_colour(src[:, :2], dst, (600, 400))

# SPDX-License-Identifier: Apache-2.0
# artcam.preset and artcam.compose against `artcam preset` and `artcam compose`: the same
# camera text, the same refusals.
import pytest

import artcam


def cli_camera(run_cli, tmp_path, name, *args):
    path = tmp_path / f"{name}.artcam"
    run_cli(*args, "-o", path)
    return path.read_text()


def test_effect_and_view_presets_equal_the_cli(run_cli, tmp_path):
    barrel = artcam.preset("barrel", k=-0.2, size=(600, 400))
    assert barrel.to_json() == cli_camera(run_cli, tmp_path, "barrel", "preset", "barrel",
                                          "--k", "-0.2", "--size", "600x400")
    assert barrel.kind == "single" and barrel.source_size == (600, 400)
    view = artcam.preset("pinhole", eye=(3, 2, -4), focal=1.5)
    assert view.to_json() == cli_camera(run_cli, tmp_path, "pinhole", "preset", "pinhole",
                                        "--eye", "3,2,-4", "--focal", "1.5")
    over = artcam.preset("composite", op="over", size=(320, 240))
    assert over.to_json() == cli_camera(run_cli, tmp_path, "over", "preset", "composite",
                                        "--op", "over", "--size", "320x240")
    twist = artcam.preset("twist-3d", object_radius=1.8)
    assert twist.to_json() == cli_camera(run_cli, tmp_path, "twist", "preset", "twist-3d",
                                         "--object-radius", "1.8")
    names = artcam.presets()
    assert {"barrel", "pinhole", "twist-3d", "aerial-perspective"} <= set(names)
    assert "cube-of-cubes" not in names
    assert "k=-0.15" in artcam.preset_listing()


def test_preset_refusals_carry_the_cli_message(run_cli, tmp_path):
    cli = run_cli("preset", "barrel", "--k", "5", "-o", tmp_path / "x.artcam", check=False)
    with pytest.raises(ValueError) as refused:
        artcam.preset("barrel", k=5)
    assert str(refused.value) in cli.stderr
    with pytest.raises(ValueError, match="unknown preset \"barel\""):
        artcam.preset("barel")
    with pytest.raises(ValueError, match="point cloud"):
        artcam.preset("cube-of-cubes")
    with pytest.raises(ValueError, match="--op"):
        artcam.preset("composite", op="sideways")
    with pytest.raises(ValueError):
        artcam.preset("barrel", k=True)


def test_compose_equals_the_cli(run_cli, samples, tmp_path):
    a = tmp_path / "a.artcam"
    b = tmp_path / "b.artcam"
    artcam.preset("barrel", k=-0.1, size=(600, 400)).write(str(a))
    artcam.preset("twist", size=(600, 400)).write(str(b))
    composed = artcam.compose(artcam.read(str(a)), artcam.read(str(b)))
    assert composed.to_json() == cli_camera(run_cli, tmp_path, "ab", "compose", a, b)
    three = artcam.compose(artcam.read(str(a)), artcam.read(str(b)), artcam.read(str(a)))
    assert three.to_json() == cli_camera(run_cli, tmp_path, "aba", "compose", a, b, a)
    with pytest.raises(ValueError, match="at least two"):
        artcam.compose(artcam.read(str(a)))
    with pytest.raises(TypeError):
        artcam.compose(artcam.read(str(a)), str(b))

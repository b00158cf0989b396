# SPDX-License-Identifier: Apache-2.0
# Shared fixtures: the artcam program of this build (to compare the module with the CLI), the
# source tree's samples, and images made in code.
import os
import pathlib
import subprocess

import numpy as np
import pytest

SOURCE = pathlib.Path(os.environ.get("ARTCAM_SOURCE_DIR", pathlib.Path(__file__).parents[2]))


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("ARTCAM_CLI")
    if not path:
        pytest.fail("ARTCAM_CLI is not set: run the tests through ctest (python/pytest)")
    return path


@pytest.fixture
def run_cli(cli):
    def run(*args, check=True):
        done = subprocess.run([cli, *map(str, args)], capture_output=True, text=True)
        if check and done.returncode != 0:
            raise AssertionError(f"artcam {' '.join(map(str, args))}: {done.stderr}")
        return done
    return run


@pytest.fixture(scope="session")
def samples():
    return SOURCE / "resources"


def gradient_photo(width=160, height=120, channels=3, dtype=np.uint8):
    """A smooth photo with detail in every channel, made in code."""
    y, x = np.mgrid[0:height, 0:width].astype(np.float64)
    planes = [x / width, y / height, 0.5 + 0.5 * np.sin(x / 7.0) * np.cos(y / 5.0), np.ones_like(x)]
    rgb = np.stack(planes[:channels], axis=-1)
    full = {np.uint8: 255, np.uint16: 65535, np.float32: 1.0}[dtype]
    if dtype == np.float32:
        return rgb.astype(np.float32)
    return np.round(rgb * full).astype(dtype)

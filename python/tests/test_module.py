# SPDX-License-Identifier: Apache-2.0
# The module's surface: every function and class the extension exports has a docstring worth
# reading and a type in the .pyi stub.
import pathlib
import re

import artcam
from artcam import _artcam


def public_names():
    return sorted(n for n in dir(_artcam) if not n.startswith("_"))


def test_every_export_is_documented_and_typed():
    stub = (pathlib.Path(artcam.__file__).parent / "__init__.pyi").read_text()
    typed = set(re.findall(r"^(?:def|class) (\w+)", stub, re.M))
    names = public_names()
    assert {"fit", "fit_lines", "fit_stmap", "fit_colour", "preset", "compose", "export_map",
            "export_project", "lens_search", "lens_camera", "read", "read_image"} <= set(names)
    for name in names:
        value = getattr(_artcam, name)
        assert name in typed, f"{name} has no type in __init__.pyi"
        assert value.__doc__ and len(value.__doc__) > 40, f"{name} has no docstring"
        assert getattr(artcam, name) is value  # re-exported as artcam.NAME

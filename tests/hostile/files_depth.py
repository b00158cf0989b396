# SPDX-License-Identifier: Apache-2.0
# Files for cases-depth.tsv: depth maps a project names that no effect can use as they are (runs
# inside make_files.py, whose oiio/put_json/project are in scope).
oiio("dp-nan.exr", "--pattern", "constant:color=nan", "64x48", "1", "-d", "float")
oiio("dp-wide.exr", "--pattern", "constant:color=2", "80x20", "1", "-d", "float")
for _name, _map in [("dp-nan.artcamproj", "dp-nan.exr"), ("dp-wide.artcamproj", "dp-wide.exr")]:
    put_json(_name, project(version=3, depth={"layers": [], "map": {"path": _map}},
                            effects=[{"effect": "aerial-perspective", "params": {}}]))

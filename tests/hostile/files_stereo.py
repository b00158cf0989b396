# SPDX-License-Identifier: Apache-2.0
# Files for cases-stereo.tsv: stereo pairs the matcher cannot take (runs inside make_files.py,
# whose oiio is in scope).
oiio("st-left.png", "--pattern", "noise:type=uniform:seed=3", "96x64", "3", "-d", "uint8")
oiio("st-other.png", "--pattern", "noise:type=uniform:seed=4", "80x64", "3", "-d", "uint8")
oiio("st-flat.png", "--pattern", "constant:color=0.5,0.5,0.5", "96x64", "3", "-d", "uint8")

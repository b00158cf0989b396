# SPDX-License-Identifier: Apache-2.0
# Files for cases-stereo.tsv: stereo pairs the matcher cannot take (runs inside make_files.py,
# whose oiio is in scope).
oiio("st-left.png", "--pattern", "noise:type=uniform:seed=3", "96x64", "3", "-d", "uint8")
oiio("st-other.png", "--pattern", "noise:type=uniform:seed=4", "80x64", "3", "-d", "uint8")
oiio("st-flat.png", "--pattern", "constant:color=0.5,0.5,0.5", "96x64", "3", "-d", "uint8")
oiio("st-depth.exr", "--pattern", "constant:color=5", "96x64", "1", "-d", "float")
put("st-many-walls.csv", ("wall,x,y\n" + "".join("w%d,%d,1\n" % (k, k % 90) for k in range(70))).encode())
put("st-nan-walls.csv", b"wall,x,y\nfront,1,1\nfront,nan,5\nfront,9,9\n")
put("st-one-wall.csv", b"wall,x,y\nfront,2,2\nfront,90,2\nfront,90,60\nfront,2,60\n")
# Projects whose compositing second image or finish cannot be taken (export refuses in one line).
put("cp-missing-second.artcamproj", b'{"format":"artcam-studio-project","version":5,"photo":"st-left.png",'
    b'"model":"auto","pairs":[],"second":{"path":"no-such-second.png"}}')
put("cp-second-folder.artcamproj", b'{"format":"artcam-studio-project","version":5,"photo":"st-left.png",'
    b'"model":"auto","pairs":[],"second":{"path":"."}}')
put("cp-empty-second.artcamproj", b'{"format":"artcam-studio-project","version":5,"photo":"st-left.png",'
    b'"model":"auto","pairs":[],"second":{}}')
put("cp-bad-finish.artcamproj", b'{"format":"artcam-studio-project","version":5,"photo":"st-left.png",'
    b'"model":"auto","pairs":[],"finish":"crayon"}')
put("cp-number-finish.artcamproj", b'{"format":"artcam-studio-project","version":5,"photo":"st-left.png",'
    b'"model":"auto","pairs":[],"finish":3}')

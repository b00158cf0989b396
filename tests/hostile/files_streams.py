# SPDX-License-Identifier: Apache-2.0
# Files for cases-streams.tsv: the first bytes of movie containers, made by hand after each
# container's published layout (ISO/IEC 14496-12 boxes, RIFF AVI, EBML, MPEG-PS/TS), so the
# readers' refusal is tested without a movie tool. Run by make_files.py with its helpers in scope.


def _box(kind, body):
    return struct.pack(">I", 8 + len(body)) + kind + body


# MP4: an ftyp box (major brand isom, minor version 512, compatible brands), then an empty mdat.
_mp4 = _box(b"ftyp", b"isom" + struct.pack(">I", 512) + b"isomiso2avc1mp41") + _box(b"mdat", b"\0" * 64)
put("mv-clip.mp4", _mp4)
# The same bytes under a still image's name: the signature decides, not the name.
put("mv-clip-named.png", _mp4)
put("mv-clip-named.heic", _mp4)
# QuickTime: ftyp "qt  ", and an old file that opens with its moov atom.
put("mv-clip.mov", _box(b"ftyp", b"qt  " + b"\0\0\2\0" + b"qt  ") + _box(b"mdat", b"\0" * 64))
put("mv-old.mov", _box(b"moov", _box(b"mvhd", b"\0" * 100)))
# AVI: RIFF size "AVI " LIST hdrl ...
put("mv-clip.avi", b"RIFF" + struct.pack("<I", 4 + 12 + 56) + b"AVI " + b"LIST" +
    struct.pack("<I", 4 + 56) + b"hdrl" + b"avih" + struct.pack("<I", 48) + b"\0" * 48)
# Matroska/WebM: the EBML header element.
_ebml = b"\x1a\x45\xdf\xa3\x9f\x42\x86\x81\x01\x42\xf7\x81\x01\x42\x82\x84webm" + b"\0" * 48
put("mv-clip.webm", _ebml)
put("mv-clip-named.jpg", _ebml)
# MPEG program stream (pack header) and transport stream (sync byte every 188 bytes).
put("mv-clip.mpg", b"\0\0\1\xba" + b"\x44\0\4\0\4\1\1\x89\xc3\xf8" + b"\0" * 50)
put("mv-clip.ts", (b"\x47\x40\x00\x10" + b"\xff" * 184) * 3)
# A name OpenImageIO gives its movie reader, on bytes no movie format starts with.
put("mv-nothing.mp4", b"\0" * 256)

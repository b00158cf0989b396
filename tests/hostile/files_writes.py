# SPDX-License-Identifier: Apache-2.0
# Files for cases-writes.tsv (the writers' faults): photos whose metadata the output cannot
# hold or no parser reads. Run by make_files.py with its helpers (put, get, ...) in scope.


def _with_chunk(png, kind, data):
    # One more chunk right after IHDR (8-byte signature + 25-byte IHDR), where every reader
    # sees it, before the pixels.
    body = kind + data
    chunk = struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)
    return png[:33] + chunk + png[33:]


def _xmp(body):
    return (b'<?xpacket begin="" id="W5M0MpCehiHzreSzNTczkc9d"?><x:xmpmeta xmlns:x="adobe:ns:meta/">'
            b'<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#"><rdf:Description '
            b'rdf:about="" xmlns:dc="http://purl.org/dc/elements/1.1/">' + body +
            b'</rdf:Description></rdf:RDF></x:xmpmeta><?xpacket end="w"?>')


_xmp_key = b"XML:com.adobe.xmp" + b"\0" * 5
_ok = get("ok.png")
# A 70 000-byte description: OpenImageIO's JPEG writer would make it one comment segment.
put("wr-big-comment.png", _with_chunk(_ok, b"tEXt", b"Description\0" + b"d" * 70000))
# An edit history of 100 000 bytes in the XMP packet (a Lightroom history is that size).
put("wr-big-xmp.png", _with_chunk(_ok, b"iTXt", _xmp_key + _xmp(
    b"<dc:description>" + b"h" * 100000 + b"</dc:description>")))
put("wr-bad-xmp.png", _with_chunk(_ok, b"iTXt", _xmp_key + _xmp(b"<dc:title>never closed")))
# Ten entities, each ten of the one before: 10^10 bytes once expanded.
_bomb = b'<?xml version="1.0"?><!DOCTYPE b [<!ENTITY a0 "aaaaaaaaaa">' + b"".join(
    b'<!ENTITY a%d "%s">' % (k, (b"&a%d;" % (k - 1)) * 10) for k in range(1, 10)) + b"]>"
put("wr-bomb-xmp.png", _with_chunk(_ok, b"iTXt", _xmp_key + _bomb + _xmp(b"<dc:title>&a9;</dc:title>")))
put_json("wr-proj-big-xmp.artcamproj", project("wr-big-xmp.png"))

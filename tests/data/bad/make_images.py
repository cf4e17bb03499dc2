#!/usr/bin/env python3
"""Writes the bad images of the bad-input corpus (tests/data/bad), Python standard library only.

Run from anywhere: python3 tests/data/bad/make_images.py. The images are committed; this script
says exactly what each one is, and remakes them byte for byte.
"""
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def chunk(kind, data, crc=None):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(
        ">I", zlib.crc32(body) if crc is None else crc)


def png(width, height, rows=None, bit_depth=8, colour_type=0, idat=None, bad_crc=False):
    """A PNG: `rows` is a list of raw scanlines (without the filter byte); `idat` overrides the
    compressed data (for images whose header promises more than they hold)."""
    ihdr = struct.pack(">IIBBBBB", width, height, bit_depth, colour_type, 0, 0, 0)
    if idat is None:
        raw = b"".join(b"\x00" + r for r in rows)
        idat = zlib.compress(raw, 9)
    crc = (zlib.crc32(b"IDAT" + idat) ^ 0xFFFFFFFF) if bad_crc else None
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", idat, crc) +
            chunk(b"IEND", b""))


def pfm(width, height, values):
    """A greyscale float PFM (little-endian: scale -1), rows bottom to top."""
    return b"Pf\n%d %d\n-1.0\n" % (width, height) + struct.pack("<%df" % len(values), *values)


def write(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)


def grey_rows(width, height):
    return [bytes((16 * (x + y)) % 256 for x in range(width)) for y in range(height)]


# Heightmaps.
values = [0.25] * 16
values[6] = float("nan")
write("nan_pixel.pfm", pfm(4, 4, values))
values[6] = float("inf")
write("inf_pixel.pfm", pfm(4, 4, values))
values[6] = 1e30
write("absurd_pixel.pfm", pfm(4, 4, values))
values[6] = -5.0
write("negative_pixel.pfm", pfm(4, 4, values))
write("strip_1x64.png", png(1, 64, grey_rows(1, 64)))
# Headers that promise enormous images over a few bytes of data: refused before allocating.
tiny_idat = zlib.compress(b"\x00" * 64, 9)
write("enormous_16000.png", png(16000, 16000, idat=tiny_idat))
write("enormous_100000.png", png(100000, 100000, idat=tiny_idat))
# Within a density map's 8192 per side, but far fewer bytes than deflate can squeeze it into.
write("enormous_8000.png", png(8000, 8000, idat=tiny_idat))
write("empty.png", b"")
write("bad_crc.png", png(8, 8, grey_rows(8, 8), bad_crc=True))
write("text.tif", b"This is not a TIFF; it is a note where an image was expected.\n")
# A PNG cut off inside its header chunk.
write("cut_header.png", png(8, 8, grey_rows(8, 8))[:20])

# Grass textures (RGBA, colour type 6).
rgba = lambda w, h: [bytes(((x * 7 + y * 13) % 256) for x in range(4 * w)) for y in range(h)]
write("texture_24x24.png", png(24, 24, rgba(24, 24), colour_type=6))
write("texture_enormous.png", png(8192, 8192, colour_type=6, idat=tiny_idat))
write("texture_text.png", b"grass, but in words\n")
# A valid 64 x 64 header over pixel data that stops after a few rows.
write("texture_truncated.png", png(64, 64, colour_type=6, idat=zlib.compress(b"\x00" * 600, 9)))

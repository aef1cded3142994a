#!/usr/bin/env python3
"""Reads 8-bit RGB(A) PNGs with the standard library alone and compares
two as the golden tests do (app/tests/cli/golden.rs): at least 40 dB
PSNR, at most 0.2 % of the pixels off by more than 2 levels in a
channel, none off by more than 6. For checks that must not need
Pillow (scripts/check_web_page.py --save-png).

    scripts/png_match.py a.png b.png

Exits 0 when they match, 1 with the reason when they do not.
"""

import math
import struct
import sys
import zlib

# The golden tests' tolerance (golden.rs: MIN_PSNR_DB, OFF_LEVELS,
# MAX_LEVELS, MAX_OFF_FRACTION).
MIN_PSNR_DB = 40.0
OFF_LEVELS = 2
MAX_LEVELS = 6
MAX_OFF_FRACTION = 0.002


def read_png(data):
    """(width, height, rows of RGB bytes) of an 8-bit, non-interlaced RGB
    or RGBA PNG's bytes; ValueError for anything else."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, idat, head = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        kind, body = data[pos + 4 : pos + 8], data[pos + 8 : pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            head = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
    if head is None:
        raise ValueError("a PNG without IHDR")
    width, height, depth, colour, _, _, interlace = head
    channels = {2: 3, 6: 4}.get(colour)
    if depth != 8 or channels is None or interlace:
        raise ValueError(f"not an 8-bit RGB(A) PNG (depth {depth}, colour type {colour})")
    raw, stride = zlib.decompress(idat), width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        kind, line = raw[start], bytearray(raw[start + 1 : start + 1 + stride])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b, c = previous[i], previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(v for i, v in enumerate(line) if i % channels < 3))
        previous = line
    return width, height, rows


def mismatch(a, b):
    """Why the decoded PNGs `a` and `b` differ beyond the goldens'
    tolerance, or None when they match."""
    if a[:2] != b[:2]:
        return f"sizes differ: {a[0]} x {a[1]} and {b[0]} x {b[1]}"
    width, height = a[:2]
    squares, worst, off_pixels = 0, 0, 0
    for row_a, row_b in zip(a[2], b[2]):
        for x in range(width):
            d = [abs(row_a[3 * x + k] - row_b[3 * x + k]) for k in range(3)]
            squares += sum(v * v for v in d)
            worst = max(worst, max(d))
            off_pixels += max(d) > OFF_LEVELS
    mse = squares / (3 * width * height)
    psnr = math.inf if mse == 0 else 10 * math.log10(255 * 255 / mse)
    off = off_pixels / (width * height)
    said = f"PSNR {psnr:.1f} dB, {off_pixels} pixels off by more than {OFF_LEVELS}, worst {worst}"
    if psnr < MIN_PSNR_DB or off > MAX_OFF_FRACTION or worst > MAX_LEVELS:
        return said
    print(f"images match: {said}")
    return None


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(sys.argv[1], "rb") as f, open(sys.argv[2], "rb") as g:
        why = mismatch(read_png(f.read()), read_png(g.read()))
    if why:
        print(f"the images differ: {why}", file=sys.stderr)
    return 1 if why else 0


if __name__ == "__main__":
    sys.exit(main())

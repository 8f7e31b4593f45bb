"""Reads 8-bit PNG images (grey, RGB, RGBA; no interlace) and compares them.

Used by the browser test of uuvsim view (view_browser.py). Standard library
only: zlib for the data, the five row filters of the PNG specification.
As a program:  pngcmp.py A.png B.png  prints how many pixels differ.
"""
import struct
import sys
import zlib

CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}  # colour type -> samples per pixel


class Image:
    def __init__(self, width, height, channels, rows):
        self.width = width
        self.height = height
        self.channels = channels
        self.rows = rows  # bytes per row, filters removed

    def rgb(self, x, y):
        row, c = self.rows[y], self.channels
        if c < 3:
            v = row[x * c]
            return (v, v, v)
        return (row[x * c], row[x * c + 1], row[x * c + 2])


def read(data):
    """An Image from the bytes of a PNG file; ValueError when it is not one we read."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG file")
    pos, idat, header = 8, [], None
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
    if header is None:
        raise ValueError("no IHDR chunk")
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in CHANNELS or interlace != 0:
        raise ValueError("unsupported PNG: depth %d, colour type %d, interlace %d"
                         % (depth, colour, interlace))
    c = CHANNELS[colour]
    raw = zlib.decompress(b"".join(idat))
    stride = width * c
    rows, prev = [], bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        kind = raw[start]
        row = bytearray(raw[start + 1:start + 1 + stride])
        if kind == 1:
            for i in range(c, stride):
                row[i] = (row[i] + row[i - c]) & 0xFF
        elif kind == 2:
            for i in range(stride):
                row[i] = (row[i] + prev[i]) & 0xFF
        elif kind == 3:
            for i in range(stride):
                left = row[i - c] if i >= c else 0
                row[i] = (row[i] + ((left + prev[i]) >> 1)) & 0xFF
        elif kind == 4:
            for i in range(stride):
                a = row[i - c] if i >= c else 0
                b = prev[i]
                cc = prev[i - c] if i >= c else 0
                p = a + b - cc
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - cc)
                pred = a if (pa <= pb and pa <= pc) else (b if pb <= pc else cc)
                row[i] = (row[i] + pred) & 0xFF
        elif kind != 0:
            raise ValueError("row %d: unknown filter %d" % (y, kind))
        rows.append(row)
        prev = row
    return Image(width, height, c, rows)


def diff_mask(a, b, box, threshold=24):
    """The pixels (x, y) inside box = (x0, y0, x1, y1) where a and b differ by
    more than threshold in any of R, G, B."""
    if (a.width, a.height) != (b.width, b.height):
        raise ValueError("images of different sizes")
    x0, y0, x1, y1 = box
    out = []
    for y in range(max(0, y0), min(a.height, y1)):
        for x in range(max(0, x0), min(a.width, x1)):
            pa, pb = a.rgb(x, y), b.rgb(x, y)
            if max(abs(pa[0] - pb[0]), abs(pa[1] - pb[1]), abs(pa[2] - pb[2])) > threshold:
                out.append((x, y))
    return out


def centroid(points):
    n = float(len(points)) or 1.0
    return (sum(p[0] for p in points) / n, sum(p[1] for p in points) / n)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.stderr.write("usage: pngcmp.py A.png B.png\n")
        sys.exit(2)
    imgs = []
    for name in sys.argv[1:]:
        with open(name, "rb") as f:
            imgs.append(read(f.read()))
    a, b = imgs
    n = len(diff_mask(a, b, (0, 0, a.width, a.height)))
    print("%d of %d pixels differ" % (n, a.width * a.height))
    sys.exit(1 if n else 0)

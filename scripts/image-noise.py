#!/usr/bin/env python3
"""The Monte-Carlo noise of a traced picture, from two renders that differ in their seed only.

    scripts/image-noise.py [--tiles] [--reference] A.png B.png

Prints the noise of one picture: the RMS of the per-pixel difference over sqrt(2), in 8-bit
display levels (sRGB, as the eye sees the PNG), over the pixels that are not background in
either. With --reference, B is a reference (a render of many more samples) and what is printed
is A's error against it: the RMS of the difference itself, which counts what a filter blurs as
well as what noise it leaves. With --tiles, also the noise of the noisiest tiles, where a picture looks least clean:
the same RMS within each 8x8 tile of at least 48 such pixels, and of those the 99th percentile.
Reads
8- and 16-bit RGB/RGBA PNGs without interlacing (what `render` writes), with the standard
library alone.
"""
import math
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"{path}: not a PNG")
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    if colour not in (2, 6) or interlace or depth not in (8, 16):
        sys.exit(f"{path}: expected an 8- or 16-bit RGB PNG without interlacing")
    channels = 3 if colour == 2 else 4
    bpp = channels * depth // 8
    stride = width * bpp
    raw = zlib.decompress(idat)
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = previous[i]
            c = previous[i - bpp] if i >= bpp else 0
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
        rows.append(bytes(line))
        previous = line
    top = (1 << depth) - 1
    pixels = []
    for line in rows:
        for x in range(width):
            px = []
            for k in range(3):
                at = x * bpp + k * depth // 8
                v = line[at] if depth == 8 else (line[at] << 8 | line[at + 1])
                px.append(v / top)
            pixels.append(px)
    # 8-bit pictures are sRGB, 16-bit ones linear (docs/trace.md).
    if depth == 8:
        pixels = [[c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in p]
                  for p in pixels]
    return width, height, pixels


def main():
    args = sys.argv[1:]
    tiles = "--tiles" in args
    reference = "--reference" in args
    args = [a for a in args if a not in ("--tiles", "--reference")]
    # Two pictures of one noise differ by sqrt(2) times it; a picture and a reference by its error.
    spread = 1 if reference else 2
    if len(args) != 2:
        sys.exit(__doc__)
    wa, ha, a = read_png(args[0])
    wb, hb, b = read_png(args[1])
    if (wa, ha) != (wb, hb):
        sys.exit("the pictures differ in size")
    # The background: the most common value of the first picture.
    counts = {}
    for p in a:
        counts[tuple(p)] = counts.get(tuple(p), 0) + 1
    background = list(max(counts, key=counts.get))
    def display(c):
        c = min(max(c, 0.0), 1.0)
        return 255 * (12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055)

    squares, count = 0.0, 0
    tile_sums = {}
    for i, (p, q) in enumerate(zip(a, b)):
        if p == background and q == background:
            continue
        pixel = sum((display(p[k]) - display(q[k])) ** 2 for k in range(3))
        squares += pixel
        count += 3
        tile = tile_sums.setdefault((i % wa // 8, i // wa // 8), [0.0, 0])
        tile[0] += pixel
        tile[1] += 1
    if count == 0:
        sys.exit("the pictures are background only")
    line = f"{math.sqrt(squares / count / spread):.2f}"
    if tiles:
        noise = sorted(math.sqrt(s / (3 * n) / spread) for s, n in tile_sums.values() if n >= 48)
        if noise:
            line += f" {noise[min(len(noise) - 1, int(0.99 * len(noise)))]:.2f}"
    print(line)


if __name__ == "__main__":
    main()

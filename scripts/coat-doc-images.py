#!/usr/bin/env python3
"""The pictures of docs/feathers.md, "Dense coats": a coat drawn thinned to the picture beside the
same coat with every barb (--full-feathers), and its POV-Ray export as instances beside every
feather built whole; prints how much each pair differs. The coat is drawn as grown
(--no-deintersect), so that the pairs compare thinning and instancing alone.

    scripts/coat-doc-images.py [HIRSUTE]     (default build/release/cli/hirsute)

Writes docs/images/feathers/coat-lod.png and coat-pov-instances.png. Standard library only.
"""
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BENCH = os.path.join(ROOT, "models", "bench")
IMAGES = os.path.join(ROOT, "docs", "images", "feathers")


def read_png(path):
    """(width, height, rows of RGB tuples) of an 8-bit RGB or RGBA PNG without interlacing."""
    data = open(path, "rb").read()
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and colour in (2, 6), f"{path}: not 8-bit RGB(A)"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    channels = 3 if colour == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            left = line[x - channels] if x >= channels else 0
            up = previous[x]
            corner = previous[x - channels] if x >= channels else 0
            if kind == 1:
                line[x] = (line[x] + left) & 255
            elif kind == 2:
                line[x] = (line[x] + up) & 255
            elif kind == 3:
                line[x] = (line[x] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                line[x] = (line[x] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 255
        rows.append([tuple(line[i:i + 3]) for i in range(0, stride, channels)])
        previous = line
    return width, height, rows


def write_png(path, rows):
    height, width = len(rows), len(rows[0])
    raw = b"".join(b"\0" + bytes(c for pixel in row for c in pixel) for row in rows)
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    with open(path, "wb") as out:
        out.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
                  + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def mean_abs(a, b):
    total = sum(abs(p - q) for ra, rb in zip(a, b) for pa, pb in zip(ra, rb) for p, q in zip(pa, pb))
    return total / (3 * len(a) * len(a[0]))


def crop(rows, x, y, w, h, scale):
    out = []
    for row in rows[y:y + h]:
        line = [pixel for pixel in row[x:x + w] for _ in range(scale)]
        out.extend([line] * scale)
    return out


def side_by_side(left, right, gap=6):
    white = (255, 255, 255)
    return [a + [white] * gap + b for a, b in zip(left, right)]


def coat(folder, density):
    for name in ("feather-coat.v", "strip.con", "brown.fea", "grey.fea", "green.fea", "blue.fea"):
        shutil.copy(os.path.join(BENCH, name), folder)
    text = open(os.path.join(BENCH, "feather-coat.l")).read()
    model = os.path.join(folder, f"coat-{density}.l")
    open(model, "w").write(re.sub(r"#define DENSITY [0-9.]+", f"#define DENSITY {density}", text))
    return model, os.path.join(folder, "feather-coat.v")


def main():
    hirsute = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "release", "cli", "hirsute")
    os.makedirs(IMAGES, exist_ok=True)
    with tempfile.TemporaryDirectory() as folder:
        model, view = coat(folder, "805")
        pictures = {}
        for name, more in (("thinned", []), ("full", ["--full-feathers"])):
            out = os.path.join(folder, name + ".png")
            subprocess.run([hirsute, "render", model, view, "-o", out, "--size", "800x600",
                            "--no-deintersect"] + more, check=True)
            pictures[name] = read_png(out)[2]
        print(f"render 800x600, 10 000 feathers: mean absolute difference "
              f"{mean_abs(pictures['thinned'], pictures['full']):.2f} levels")
        write_png(os.path.join(IMAGES, "coat-lod.png"),
                  side_by_side(crop(pictures["full"], 330, 240, 160, 120, 2),
                               crop(pictures["thinned"], 330, 240, 160, 120, 2)))
        model, view = coat(folder, "80.5")
        for name, more in (("instanced", []), ("whole", ["--full-feathers"])):
            pov = os.path.join(folder, name + ".pov")
            subprocess.run([hirsute, "export", model, view, "--pov", pov, "--size", "320x240",
                            "--render", "--no-deintersect"] + more, check=True)
            pictures[name] = read_png(os.path.join(folder, name + ".png"))[2]
        print(f"POV-Ray 320x240, 1 000 feathers: mean absolute difference "
              f"{mean_abs(pictures['instanced'], pictures['whole']):.2f} levels")
        write_png(os.path.join(IMAGES, "coat-pov-instances.png"),
                  side_by_side(pictures["whole"], pictures["instanced"]))


if __name__ == "__main__":
    main()

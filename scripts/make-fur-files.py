#!/usr/bin/env python3
"""Writes the generated files of the fur models with nothing but the standard library: their
colour maps (cpfg takes the background from colour 0), the droplets of
models/fur-square/word.v, which write a word into the square's wetness mask (Silva et al. 2010,
Fig. 12) one droplet every few hundredths along the strokes of the letters, and the two coat
textures of models/fur-square/spotted.v (stripes, spots), which `@Ut` chooses between.

    scripts/make-fur-files.py
"""
import math
import pathlib
import random
import struct
import zlib

ROOT = pathlib.Path(__file__).resolve().parent.parent


def write_map(path, background, *first):
    """A cpfg colour map: 256 RGB colours of one byte each; colour 0 is the background, the
    rest a grey ramp, colours 1, 2, ... the `first` ones when given."""
    colours = [background] + [(i, i, i) for i in range(1, 256)]
    for i, colour in enumerate(first):
        colours[1 + i] = colour
    path.write_bytes(bytes(c for rgb in colours for c in rgb))
    print(f"wrote {path.relative_to(ROOT)}")


# The strokes of the letters F, U and R in a unit cell (x to the right, y up), as polylines;
# the bowl of the R and the bottom of the U as arcs.
def arc(cx, cy, r, a0, a1, steps=12):
    return [(cx + r * math.cos(math.radians(a0 + (a1 - a0) * i / steps)),
             cy + r * math.sin(math.radians(a0 + (a1 - a0) * i / steps))) for i in range(steps + 1)]


LETTERS = {
    "F": [[(0.1, 0.0), (0.1, 1.0), (0.8, 1.0)], [(0.1, 0.52), (0.62, 0.52)]],
    "U": [[(0.1, 1.0), (0.1, 0.35)] + arc(0.45, 0.35, 0.35, 180, 360) + [(0.8, 1.0)]],
    "R": [[(0.1, 0.0), (0.1, 1.0), (0.45, 1.0)] + arc(0.45, 0.75, 0.25, 90, -90) +
          [(0.1, 0.5)], [(0.4, 0.5), (0.85, 0.0)]],
}


def droplets(word, left, bottom, height, spacing, radius, wetness):
    lines = []
    for k, letter in enumerate(word):
        x0 = left + k * height * 0.95
        for stroke in LETTERS[letter]:
            for (ax, ay), (bx, by) in zip(stroke, stroke[1:]):
                length = math.hypot(bx - ax, by - ay) * height
                n = max(1, round(length / spacing))
                for i in range(n):
                    t = i / n
                    u = x0 + (ax + (bx - ax) * t) * height
                    v = bottom + (ay + (by - ay) * t) * height
                    lines.append(f"droplet: {u:.4f} {v:.4f} {radius} {wetness}")
            ex, ey = stroke[-1]
            lines.append(f"droplet: {x0 + ex * height:.4f} {bottom + ey * height:.4f} {radius} {wetness}")
    return lines


def write_png(path, width, height, colour_at):
    """An 8-bit RGB PNG of colour_at(x, y) (row 0 at the top)."""
    rows = b"".join(b"\0" + bytes(c for x in range(width) for c in colour_at(x, y))
                    for y in range(height))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
                     + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))
    print(f"wrote {path.relative_to(ROOT)}")


def coat_textures(folder):
    """A tawny coat with dark wavy stripes, and the same coat with dark rosette spots: two
    textures of one size, so that a model shows which one `@Ut` picked."""
    size = 128
    tawny, dark = (214, 160, 82), (48, 32, 22)

    def stripes(x, y):
        wave = 0.5 + 0.5 * math.sin(2 * math.pi * (x / size * 5 + 0.12 * math.sin(2 * math.pi * y / size * 2)))
        return dark if wave > 0.78 else tawny

    rng = random.Random(7)
    spots = [(rng.uniform(0, size), rng.uniform(0, size), rng.uniform(6, 11)) for _ in range(22)]

    def spotted(x, y):
        for cx, cy, r in spots:
            dx = min(abs(x - cx), size - abs(x - cx))  # the texture repeats
            dy = min(abs(y - cy), size - abs(y - cy))
            d = math.hypot(dx, dy)
            if 0.45 * r < d < r:
                return dark
        return tawny

    write_png(folder / "stripes.png", size, size, stripes)
    write_png(folder / "spots.png", size, size, spotted)


def main():
    write_map(ROOT / "models/fur-torus/torus.map", (235, 235, 228), (150, 98, 52))
    write_map(ROOT / "models/fur-square/square.map", (232, 234, 236), (196, 150, 96))
    write_map(ROOT / "models/fur-curls/curls.map", (236, 236, 232), (178, 142, 104))
    # Silver-grey catkin fur, the reddish-brown twig.
    write_map(ROOT / "models/pussy-willow/pussy-willow.map", (226, 232, 238), (196, 194, 190),
              (112, 52, 38))
    word = ROOT / "models/fur-square/word.v"
    text = ["/* The furry square with a word written in its wetness mask (Silva et al. 2010, Fig. 12):",
            "   droplets along the strokes of the letters, written by scripts/make-fur-files.py. */",
            '#include "square.v"']
    text += droplets("FUR", 0.1, 0.36, 0.28, 0.03, 0.04, 1)
    word.write_text("\n".join(text) + "\n")
    print(f"wrote {word.relative_to(ROOT)}")
    coat_textures(ROOT / "models/fur-square")


if __name__ == "__main__":
    main()

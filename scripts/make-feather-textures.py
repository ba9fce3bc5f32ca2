#!/usr/bin/env python3
"""Paints the feather textures the models use (peacock eye, hawk bars, budgie scallops, the
stripes of models/feather-parameters) into PNG files, and writes the colour maps that give the
feather models a light background (cpfg takes the background from colour 0), with nothing but
the standard library, so that no image is downloaded.

The textures are mapped on the vane (docs/feathers.md, "Textures"): u runs across the feather
from the right vane's edge (0) to the left vane's (1), v along it from the base (0) to the tip
(1). The image's last row is v = 0 and its first row v = 1, as GL reads texture coordinates:
the image is painted the way up the feather stands.

    scripts/make-feather-textures.py            # writes every texture beside its model
"""
import math
import pathlib
import struct
import zlib

ROOT = pathlib.Path(__file__).resolve().parent.parent
SIZE = 256


def write_png(path, size, pixel):
    rows = bytearray()
    for r in range(size):
        rows.append(0)  # no filter
        v = 1 - r / (size - 1)
        for c in range(size):
            u = c / (size - 1)
            rgb = pixel(u, v)
            rows.extend(max(0, min(255, round(255 * x))) for x in rgb)

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    png = b"\x89PNG\r\n\x1a\n"
    png += chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(bytes(rows), 9))
    png += chunk(b"IEND", b"")
    path.write_bytes(png)
    print(f"wrote {path.relative_to(ROOT)}")


def write_map(path, background, *first):
    """A cpfg colour map: 256 RGB colours of one byte each; colour 0 is the background, the
    rest a grey ramp, colours 1, 2, ... the `first` ones when given."""
    colours = [background] + [(i, i, i) for i in range(1, 256)]
    for i, colour in enumerate(first):
        colours[1 + i] = colour
    path.write_bytes(bytes(c for rgb in colours for c in rgb))
    print(f"wrote {path.relative_to(ROOT)}")


def mix(a, b, t):
    t = max(0.0, min(1.0, t))
    return tuple(x + (y - x) * t for x, y in zip(a, b))


def smooth_step(e0, e1, x):
    t = max(0.0, min(1.0, (x - e0) / (e1 - e0)))
    return t * t * (3 - 2 * t)


def peacock(u, v):
    # The ocellus near the tip: rings of navy, blue, turquoise, bronze and green around an
    # elliptic centre, on a bronze-green body (Streit & Heidrich 2002, Fig. 12).
    d = math.hypot((u - 0.5) / 0.34, (v - 0.8) / 0.13)
    rings = [(0.32, (0.03, 0.05, 0.25)), (0.5, (0.06, 0.2, 0.62)), (0.66, (0.05, 0.5, 0.5)),
             (0.8, (0.62, 0.44, 0.14)), (1.0, (0.22, 0.5, 0.14))]
    body = mix((0.42, 0.4, 0.12), (0.3, 0.45, 0.14), v)
    colour = body
    for i in range(len(rings) - 1, -1, -1):
        radius, ring = rings[i]
        colour = mix(ring, colour, smooth_step(radius - 0.03, radius + 0.03, d))
    return colour


def hawk(u, v):
    # Brown with dark transverse bars that follow the feather's rounded tip, pale edges.
    across = abs(u - 0.5) * 2
    phase = (v + 0.08 * across * across) / 0.11
    bar = smooth_step(0.55, 0.7, 0.5 + 0.5 * math.cos(2 * math.pi * phase))
    colour = mix((0.58, 0.4, 0.22), (0.2, 0.12, 0.07), bar)
    colour = mix(colour, (0.85, 0.76, 0.6), smooth_step(0.8, 1.0, across) * 0.6)
    return mix(colour, (0.15, 0.1, 0.06), smooth_step(0.9, 1.0, v))


def budgie(u, v):
    # Green, a black scallop band before the tip and a yellow fringe (a budgerigar's back).
    across = abs(u - 0.5) * 2
    band = 0.78 - 0.1 * across * across
    colour = mix((0.18, 0.5, 0.12), (0.4, 0.78, 0.2), v)
    colour = mix(colour, (0.04, 0.04, 0.03), smooth_step(band - 0.02, band + 0.02, v))
    return mix(colour, (0.95, 0.85, 0.25), smooth_step(band + 0.1, band + 0.13, v))


def stripes(u, v):
    # Dark and pale bands across v with a slight darkening towards u = 0, to show which way each
    # mapping runs (models/feather-parameters/texture.l: barb, vane and growth).
    band = smooth_step(0.35, 0.65, 0.5 + 0.5 * math.cos(2 * math.pi * v * 5))
    colour = mix((0.9, 0.82, 0.62), (0.3, 0.16, 0.08), band)
    return mix((0.55, 0.3, 0.15), colour, 0.6 + 0.4 * u)


def main():
    write_png(ROOT / "models/peacock-feather/peacock-eye.png", SIZE, peacock)
    write_png(ROOT / "models/feather-types/hawk.png", SIZE, hawk)
    write_png(ROOT / "models/feather-types/budgie.png", SIZE, budgie)
    write_png(ROOT / "models/feather-parameters/stripes.png", SIZE, stripes)
    for model in ("feather-types", "feather-interpolation", "feather-growth"):
        write_map(ROOT / f"models/{model}/{model}.map", (236, 235, 228))
    # colour: 2 in models/feather-parameters is a slate blue.
    write_map(ROOT / "models/feather-parameters/feather-parameters.map", (236, 235, 228),
              (196, 160, 140), (70, 90, 140))
    # The coat's patch of skin is colour 1.
    write_map(ROOT / "models/feather-coat/feather-coat.map", (236, 235, 228), (196, 160, 140))
    # Feather grass against a dusk sky: its leaves (2) and the awns' columns (3).
    write_map(ROOT / "models/feather-grass/feather-grass.map", (38, 46, 60), (128, 128, 128),
              (82, 126, 58), (128, 92, 52))
    # The pasque flower: its stalk (2) and the head's receptacle (3) against a dark ground.
    write_map(ROOT / "models/pulsatilla/pulsatilla.map", (30, 34, 30), (128, 128, 128),
              (96, 104, 70), (110, 86, 70))


if __name__ == "__main__":
    main()

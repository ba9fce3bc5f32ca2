#!/usr/bin/env python3
"""Writes the small HDR environment map of models/wild-crocus (garden-evening.exr): a
latitude-longitude map, 128x64 texels, of an evening sky over a lawn, as an uncompressed
OpenEXR file of half floats, made by the OpenEXR layout alone (magic, header, line offsets,
scanlines) so that it needs no library.

The map (docs/trace.md, "Environment map"): a sky from a pale warm horizon to a deeper blue
zenith, a low sun 12 degrees up, 4 degrees across and some 3000 times the sky's radiance, a
brighter glow about it, and below the horizon a dim green ground. Its middle column looks along
+z; the sun stands at a quarter of the width, towards -x.

    scripts/make-environment-map.py models/wild-crocus/garden-evening.exr
"""
import math
import struct
import sys

WIDTH, HEIGHT = 128, 64
SUN_ELEVATION = math.radians(12)
SUN_AZIMUTH = -math.pi / 2  # towards -x: the map's column at u = 0.25


def direction(u, v):
    theta = math.pi * v
    phi = 2 * math.pi * (u - 0.5)
    s = math.sin(theta)
    # (along +z, up, along +x): the map's frame for up = +y.
    return (s * math.cos(phi), math.cos(theta), s * math.sin(phi))


def radiance(u, v):
    front, up, side = direction(u, v)
    sun = (math.cos(SUN_ELEVATION) * math.cos(SUN_AZIMUTH), math.sin(SUN_ELEVATION),
           math.cos(SUN_ELEVATION) * math.sin(SUN_AZIMUTH))
    cos_gamma = front * sun[0] + up * sun[1] + side * sun[2]
    gamma = math.acos(max(-1.0, min(1.0, cos_gamma)))
    if up < 0:
        return (0.05, 0.08, 0.03)  # the lawn, dim green
    height = up
    sky = (0.55 - 0.35 * height, 0.5 - 0.2 * height, 0.55 + 0.1 * height)
    glow = 1.6 * math.exp(-gamma / 0.25)
    sky = (sky[0] + glow, sky[1] + 0.7 * glow, sky[2] + 0.35 * glow)
    if gamma < math.radians(2.0):
        return (2000.0, 1500.0, 1000.0)
    return sky


def attribute(name, kind, value):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make-environment-map.py OUTPUT.exr")
    channels = b"".join(
        c.encode() + b"\0" + struct.pack("<iB3xii", 1, 0, 1, 1) for c in ("B", "G", "R")) + b"\0"
    header = b"".join([
        attribute("channels", "chlist", channels),
        attribute("compression", "compression", b"\0"),
        attribute("dataWindow", "box2i", struct.pack("<iiii", 0, 0, WIDTH - 1, HEIGHT - 1)),
        attribute("displayWindow", "box2i", struct.pack("<iiii", 0, 0, WIDTH - 1, HEIGHT - 1)),
        attribute("lineOrder", "lineOrder", b"\0"),
        attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0)),
        attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)),
        attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)),
    ]) + b"\0"
    start = b"\x76\x2f\x31\x01" + struct.pack("<i", 2) + header
    lines = []
    for y in range(HEIGHT):
        texels = [radiance((x + 0.5) / WIDTH, (y + 0.5) / HEIGHT) for x in range(WIDTH)]
        data = b"".join(struct.pack("<%de" % WIDTH, *[t[c] for t in texels]) for c in (2, 1, 0))
        lines.append(struct.pack("<ii", y, len(data)) + data)
    offset = len(start) + 8 * HEIGHT
    table = b""
    for line in lines:
        table += struct.pack("<Q", offset)
        offset += len(line)
    with open(sys.argv[1], "wb") as out:
        out.write(start + table + b"".join(lines))


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""The halo of a backlit hairy plant, from its picture and its --no-hairs twin (docs/trace.md).

    scripts/halo-figures.py HAIRS.png BARE.png

Prints, on each pixel's grey level (the mean of its sRGB channels, 0-255):
  brighter  the share of the picture's pixels more than 40 levels brighter with hairs than bare;
  band      how far the halo reaches beyond the bare silhouette: the pixels of the background
            (bare) more than 40 levels brighter with hairs, over the silhouette's edge pixels
            (a mean width), and the 90th percentile of their distance from the plant in pixels;
  brightest the brightest grey level with hairs and bare.
Reads the PNGs that `render` writes with the standard library alone.
"""
import collections
import importlib.util
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("image_noise", os.path.join(here, "image-noise.py"))
image_noise = importlib.util.module_from_spec(spec)
spec.loader.exec_module(image_noise)


def level(linear):
    """A linear value as its 8-bit sRGB level."""
    c = linear * 12.92 if linear <= 0.0031308 else 1.055 * linear ** (1 / 2.4) - 0.055
    return 255 * min(max(c, 0.0), 1.0)


def grey(image):
    width, height, pixels = image
    return width, height, [sum(level(c) for c in p[:3]) / 3 for p in pixels]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    hairs = image_noise.read_png(sys.argv[1])
    bare = image_noise.read_png(sys.argv[2])
    if hairs[:2] != bare[:2]:
        sys.exit("the two pictures differ in size")
    width, height, h = grey(hairs)
    _, _, b = grey(bare)
    background = collections.Counter(round(v) for v in b).most_common(1)[0][0]
    plant = [abs(v - background) > 3 for v in b]
    n = width * height
    brighter = [h[i] - b[i] > 40 for i in range(n)]
    # Chessboard distance from the bare plant, by a breadth-first walk.
    distance = [-1] * n
    queue = collections.deque(i for i in range(n) if plant[i])
    for i in queue:
        distance[i] = 0
    edge = 0
    while queue:
        i = queue.popleft()
        x, y = i % width, i // width
        for dy in (-1, 0, 1):
            for dx in (-1, 0, 1):
                u, v = x + dx, y + dy
                if 0 <= u < width and 0 <= v < height and distance[v * width + u] < 0:
                    distance[v * width + u] = distance[i] + 1
                    queue.append(v * width + u)
    for i in range(n):
        if distance[i] == 1:
            edge += 1
    halo = sorted(distance[i] for i in range(n) if brighter[i] and not plant[i])
    p90 = halo[int(0.9 * (len(halo) - 1))] if halo else 0
    print(f"brighter  {100 * sum(brighter) / n:.1f}% of pixels (> 40 levels over bare)")
    print(f"band      {len(halo) / max(edge, 1):.2f} px mean width beyond the silhouette, "
          f"90th percentile {p90} px")
    print(f"brightest {max(h):.0f} with hairs, {max(b):.0f} bare")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Writes examples/terrain.hf, the 64x64 height field used by examples/heightfield.ray.

Format (spec 3.14): a little-endian 32-bit integer N, then N rows of N 32-bit floats; row i,
column j is the height at (x, y) = (j/(N-1), i/(N-1)) of the unit square. The terrain is a
sum of smooth hills and a ridge with a little deterministic ripple, falling to the
base level 0.02 at the edges (an island), heights in about
[0.02, 0.5], with a basin for a lake whose floor is flat at 0.02.
Usage: python3 examples/make_terrain.py [output.hf]
"""
import math
import struct
import sys

N = 64


def height(x, y):
    hills = [  # (centre x, centre y, peak height, width)
        (0.30, 0.70, 0.40, 0.16),
        (0.70, 0.75, 0.30, 0.12),
        (0.55, 0.40, 0.22, 0.10),
        (0.15, 0.25, 0.15, 0.12),
        (0.85, 0.30, 0.18, 0.09),
    ]
    h = 0.04
    for cx, cy, peak, width in hills:
        d2 = (x - cx) ** 2 + (y - cy) ** 2
        h += peak * math.exp(-d2 / (2 * width * width))
    ridge = 0.12 * math.exp(-((y - 0.9 + 0.3 * x) ** 2) / 0.004)
    ripple = 0.012 * math.sin(23 * x + 5 * y) * math.sin(19 * y - 7 * x)
    h += ridge + ripple
    # An island: the relief falls to the base level at the square's edges.
    h = 0.02 + (h - 0.02) * (math.sin(math.pi * x) * math.sin(math.pi * y)) ** 0.6
    # A basin in the lower right for a lake; its floor is flat at 0.02.
    h -= 0.3 * math.exp(-((x - 0.62) ** 2 + (y - 0.15) ** 2) / (2 * 0.09 * 0.09))
    return max(h, 0.02)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "terrain.hf"
    with open(out, "wb") as f:
        f.write(struct.pack("<i", N))
        for i in range(N):
            y = i / (N - 1)
            f.write(struct.pack("<%df" % N, *(height(j / (N - 1), y) for j in range(N))))


if __name__ == "__main__":
    main()

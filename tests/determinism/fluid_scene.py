#!/usr/bin/env python3
"""Writes a fluid-like implicit scene: N Gascuel points 0.6 apart on a seeded, confined
random walk (more than 2,048 patches, so the object grows per-cell trees and makes its
neighbour lists lazily, on whichever thread first needs each patch).

Usage: fluid_scene.py OUT.ray [N]
"""
import math
import random
import sys


def main():
    out, n = sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 3000
    rng = random.Random(1000 + n)
    half = 0.5 * (n * 0.6 * math.pi * 0.45 ** 2 / 0.05) ** (1 / 3)
    p, d = [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]
    lines = ["eyep %g %g %g\nlookp 0 0 0\nup 0 0 1\nfov 45\n" % (3 * half, -2.5 * half, 2 * half),
             "light 1 point %g %g %g\n" % (2 * half, -4 * half, 5 * half),
             "light 0.5 point %g %g %g\n" % (-4 * half, -half, 3 * half),
             "surface white ambient 0.05 0.05 0.05 diffuse 0.6 0.6 0.6 "
             "specular 0.5 0.5 0.5 specpow 20\n",
             "plane white 0 0 %g 0 0 1\n" % (-half - 1),
             "implicit white\n field linear 0.45 2 1\n"]
    for i in range(n):
        lines.append(" point p%d %.6f %.6f %.6f\n" % (i, p[0], p[1], p[2]))
        d = [d[k] + 0.35 * rng.gauss(0, 1) for k in range(3)]
        norm = math.sqrt(sum(x * x for x in d))
        d = [x / norm for x in d]
        for k in range(3):
            if abs(p[k] + 0.6 * d[k]) > half:
                d[k] = -d[k]
        p = [p[k] + 0.6 * d[k] for k in range(3)]
    lines.append("end\n")
    with open(out, "w") as fh:
        fh.write("".join(lines))


if __name__ == "__main__":
    main()

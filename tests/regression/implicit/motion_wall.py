#!/usr/bin/env python3
"""No hole in a thin wall crossed by a fast skeleton within one exposure (issue 14, check
c; motion_wall.ray). At random ray times over the whole shutter, and densely around the
crossing (the blob's centre within 0.5 of the wall), rays across the wall and rays
through the blob's centre must all hit, no farther than the wall's or the blob's own
surface alone (the field is a sum of non-negative terms, so the blended surface encloses
each lone one: wall x = ±0.06, blob radius 0.3), and where the default method (patches)
hits, the ground truth (-m exact, evaluating every term at the ray's time) must agree to
1e-6. Usage: motion_wall.py RAYQUERY SCENE"""
import random
import subprocess
import sys

rayquery, scene = sys.argv[1:3]
rng = random.Random(19)
queries = []  # (line, farthest allowed t)
for k in range(2000):
    time = rng.uniform(0, 1) if k % 2 else rng.uniform(0.5 - 1 / 12, 0.5 + 1 / 12)
    y, z = rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5)
    if k % 4 < 2:  # across the wall, from either side
        if k % 8 < 4:
            queries.append(("-5 %r %r 1 0 0 0 1e14 %r" % (y, z, time), 5 - 0.06))
        else:
            queries.append(("5 %r %r -1 0 0 0 1e14 %r" % (y, z, time), 5 - 0.06))
    else:  # down through the blob's centre
        x = -3 + 6 * time
        queries.append(("%r 0 5 0 0 -1 0 1e14 %r" % (x, time), 5 - 0.3))


def run(*options):
    out = subprocess.run([rayquery, *options, scene], input="\n".join(q for q, _ in queries),
                         capture_output=True, text=True, check=True).stdout.split("\n")
    return [l.split() for l in out if l]


fast, exact = run(), run("-m", "exact")
failures = 0
for (query, farthest), a, b in zip(queries, fast, exact):
    ok = (a[0] == "hit" and b[0] == "hit" and float(a[1]) <= farthest + 1e-6 and
          abs(float(a[1]) - float(b[1])) <= 1e-6)
    if not ok:
        failures += 1
        print("%s: patches %s, exact %s (farthest %r)" % (query, a[:2], b[:2], farthest))
print("%d rays across the wall and through the moving blob, %d failures"
      % (len(queries), failures))
sys.exit(1 if failures else 0)

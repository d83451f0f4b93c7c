#!/usr/bin/env python3
"""rayquery's time column against static scenes (issue 14, check b): for 1,000 random
(ray, time) pairs, the first hit of the moving scene (shutter open, each query giving its
ray time) must equal that of the same scene prepared statically at that time (shutter
closed, `starttime` = the time): the same hit or miss, and t within 1e-6 (the scene's root
tolerance is 1e-8). A control run asks the moving scene at the frame's start time instead
and must disagree on some rays, so the check can fail.
Usage: motion_rayquery.py RAYQUERY SCENE WORKDIR"""
import concurrent.futures
import math
import os
import random
import subprocess
import sys

rayquery, scene, work = sys.argv[1:4]
os.makedirs(work, exist_ok=True)
text = open(scene).read()
assert "shutter 1\n" in text
rng = random.Random(14)
queries = []
for _ in range(1000):
    # Origins on a sphere of radius 6, aimed at a random point of the skeletons' region.
    u, v = rng.uniform(-1, 1), rng.uniform(0, 2 * math.pi)
    o = (6 * math.sqrt(1 - u * u) * math.cos(v), 6 * math.sqrt(1 - u * u) * math.sin(v), 6 * u)
    aim = [rng.uniform(-1.2, 1.2) for _ in range(3)]
    d = [a - b for a, b in zip(aim, o)]
    n = math.sqrt(sum(x * x for x in d))
    queries.append((o, [x / n for x in d], rng.uniform(0, 1)))


def line(o, d, extra=""):
    return " ".join(repr(x) for x in list(o) + list(d)) + extra + "\n"


def run(scene_path, lines):
    out = subprocess.run([rayquery, scene_path], input="".join(lines), capture_output=True,
                         text=True, check=True).stdout.split("\n")
    return [l.split() for l in out if l]


def agree(a, b):
    if a[0] != b[0]:
        return False
    return a[0] == "miss" or abs(float(a[1]) - float(b[1])) <= 1e-6


moving = run(scene, [line(o, d, " 0 1e14 %r" % t) for o, d, t in queries])
at_start = run(scene, [line(o, d) for o, d, _ in queries])


def static_answer(k):
    o, d, t = queries[k]
    static_path = os.path.join(work, "static%d.ray" % k)
    with open(static_path, "w") as f:
        f.write(text.replace("shutter 1\n", "starttime %r\n" % t))
    answer = run(static_path, [line(o, d)])[0]
    os.remove(static_path)
    return answer


with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
    statics = list(pool.map(static_answer, range(len(queries))))
failures, hits, control_differs = 0, 0, 0
for k, (o, d, t) in enumerate(queries):
    static = statics[k]
    hits += static[0] == "hit"
    if not agree(moving[k], static):
        failures += 1
        print("query %d at time %r: moving %s, static %s" % (k, t, moving[k][:2], static[:2]))
    control_differs += not agree(at_start[k], static)
print("%d queries, %d static hits, %d disagreements; control (start time) differs on %d"
      % (len(queries), hits, failures, control_differs))
if failures or hits < 200 or control_differs < 20:
    sys.exit(1)

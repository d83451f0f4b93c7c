#!/usr/bin/env python3
"""The parser's parallel runs of primitives (libshade/parser.cpp) against its serial parse.

Generates scenes of long runs of primitives (several megabytes, so that runs of several
waves start) broken by everything that must stop a run and be parsed the serial way: a
degenerate triangle (a warning), a comment many pieces long whose lines start with
primitive keywords, a textured primitive, applysurf, a named object and its instance, an
aggregate's end, polygons spelled `polygon`, transforms. Each is rendered on one thread
(no parallel runs) and on two and three, and the test requires the same exit status, the
same diagnostics (with their lines) and byte-identical images, and that the verbose report
shows primitives parsed in parallel on two threads (so the runs did happen). A second scene
has a syntax error deep in a run: every thread count must report it at the line the
generator put it on.

Usage: parallel_parse_matches_serial.py RAYSHADE WORKDIR
"""
import os
import random
import subprocess
import sys

RUN = 25000  # primitives per run: about 1.5 MB of text, a few waves of pieces


class Scene:
    def __init__(self):
        self.lines = []

    def add(self, text):
        self.lines.append(text)
        return len(self.lines)  # the line number of what was added

    def text(self):
        return "\n".join(self.lines) + "\n"


def triangles(scene, rng, count, surface="red"):
    for _ in range(count):
        x, y, z = rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-4, 4)
        scene.add("triangle %s %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f" % (
            surface, x, y, z, x + 0.05, y, z, x, y + 0.05, z + 0.02))


def build(error_at=None):
    """The scene text, the lines of its expected warnings and of the error (or None)."""
    rng = random.Random(17)
    s = Scene()
    for line in ("eyep 0 -14 4", "lookp 0 0 0", "fov 40", "screen 48 48",
                 "light 1 point 6 -8 12", "surface red diffuse 0.8 0.2 0.2",
                 "surface blue diffuse 0.2 0.3 0.8", "grid 8 8 8"):
        s.add(line)
    warnings = []
    triangles(s, rng, RUN)
    warnings.append(s.add("triangle red 1 1 1 1 1 1 1 1 1"))  # degenerate
    triangles(s, rng, RUN // 4)
    s.add("/* a long comment whose lines look like statements")
    for _ in range(RUN // 4):
        s.add("triangle red 0 0 0 1 0 0 0 1 0")
    s.add("*/")
    triangles(s, rng, RUN)
    s.add("sphere blue 0.3 1 1 1 texture checker red")
    s.add("applysurf blue")
    for _ in range(RUN // 2):  # the scope's default surface, and transforms
        s.add("sphere 0.04 %.4f %.4f %.4f translate 0 0 0.01" % (
            rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-4, 4)))
    s.add("name marker sphere red 0.2 0 0 0")
    for i in range(RUN // 2):
        s.add("polygon red")
        x, y = rng.uniform(-4, 4), rng.uniform(-4, 4)
        s.add("  %.4f %.4f -3 %.4f %.4f -3 %.4f %.4f -3" % (x, y, x + 0.06, y, x, y + 0.06))
        if error_at is not None and i == RUN // 4:
            error_at = s.add("sphere red 0.1 1 2 cone")  # a keyword where a number belongs
    s.add("object marker translate 2 0 0")
    s.add("end")
    for _ in range(RUN // 2):  # a run at the top level, after the grid
        x, y, z = rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-4, 4)
        s.add("cone blue 0.03 %.4f %.4f %.4f 0.01 %.4f %.4f %.4f" % (x, y, z, x, y, z + 0.1))
    return s.text(), warnings, error_at


def render(rayshade, scene, work, tag, threads):
    image = os.path.join(work, tag + ".png")
    stats = os.path.join(work, tag + ".txt")
    if os.path.exists(image):
        os.remove(image)
    r = subprocess.run([rayshade, "-t", str(threads), "-v", "-V", stats, "-O", image, scene],
                       capture_output=True, text=True)
    data = open(image, "rb").read() if os.path.exists(image) else None
    report = open(stats).read() if os.path.exists(stats) else ""
    # The progress lines depend on how the rows are shared between threads.
    diagnostics = "".join(l for l in r.stderr.splitlines(True) if not l.startswith("frame "))
    return r.returncode, diagnostics, data, report


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def main():
    rayshade, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)

    text, warnings, _ = build()
    scene = os.path.join(work, "runs.ray")
    with open(scene, "w") as fh:
        fh.write(text)
    serial = render(rayshade, scene, work, "serial", 1)
    if serial[0] != 0 or serial[2] is None:
        fail("the serial render failed: %s" % serial[1])
    for line in warnings:
        if ("runs.ray:%d:" % line) not in serial[1]:
            fail("the serial parse did not warn at line %d:\n%s" % (line, serial[1]))
    if "parsed in parallel" in serial[3]:
        fail("one thread ran parallel runs")
    for threads in (2, 3):
        status, stderr, image, report = render(rayshade, scene, work, "t%d" % threads, threads)
        if status != serial[0]:
            fail("%d threads: exit status %d, serially %d" % (threads, status, serial[0]))
        if stderr != serial[1]:
            fail("%d threads: diagnostics differ:\n%s\n--- serially:\n%s" % (threads, stderr, serial[1]))
        if image != serial[2]:
            fail("%d threads: the image differs from the serial parse's" % threads)
        parallel = [l for l in report.splitlines() if l.startswith("Primitives parsed in parallel")]
        if not parallel:
            fail("%d threads: no primitive was parsed in parallel" % threads)
    print("same diagnostics and image on 1, 2 and 3 threads; %s" % parallel[0])

    text, _, error_line = build(error_at=True)
    bad = os.path.join(work, "error.ray")
    with open(bad, "w") as fh:
        fh.write(text)
    results = [render(rayshade, bad, work, "error_t%d" % t, t) for t in (1, 2, 3)]
    for threads, (status, stderr, image, _) in zip((1, 2, 3), results):
        if status == 0 or image is not None:
            fail("%d threads: the syntax error was not fatal (or left an image)" % threads)
        if ("error.ray:%d:" % error_line) not in stderr:
            fail("%d threads: the error is not reported at line %d:\n%s" % (threads, error_line, stderr))
        if stderr != results[0][1]:
            fail("%d threads: diagnostics differ from one thread's" % threads)
    print("the syntax error at line %d reported the same on 1, 2 and 3 threads" % error_line)


if __name__ == "__main__":
    main()

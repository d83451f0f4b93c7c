#!/usr/bin/env python3
"""Cost of skeleton motion blur (issue 14) on the 1,000-point chain of bench/implicit.py.

The chain (blob points, R = 1, T = 0.6: a tube about 0.95 thick) is rendered with method
patches, one thread, --samples² samples per pixel (default 3: 9, the square nearest 8),
twice: blurred, every point moving by 0.95 along x during the shutter (`shutter 1`, points
at `x + 0.95*time`), and static, the same scene with the shutter closed (the chain sharp at
time 0). Runs are interleaved, --repeat times. Printed: the median render CPU time of each
(the child's user + system time, less sensitive to the shared machine than wall time), the
ratio blurred / static (target within 2x), and from `rayshade -v` the implicit field +
gradient + bound evaluations per ray and per intersection call of each. With --callgrind,
each variant also runs once under valgrind's callgrind and the instruction counts and their
ratio are printed: unlike CPU time, they do not depend on the machine's load (valgrind is
about 50 times slower: use a small --size).
"""
import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import implicit as chain  # noqa: E402  (the chain, camera and counters of bench/implicit.py)

SPEED = 0.95  # x distance moved during the shutter: about the tube's thickness


def scene(points, size, samples, blurred):
    text = chain.rayshade_scene(points, "patches")
    text = text.replace("screen 512 512\n", "screen %d %d\nsample %d\n" % (size, size, samples))
    if not blurred:
        return text
    lines = []
    for line in text.splitlines(True):
        if line.startswith(" point p"):
            name, x, y, z = line.split()[1:]
            line = " point %s (%s + %g*time) %s %s\n" % (name, x, SPEED, y, z)
        lines.append(line)
    return "shutter 1\n" + "".join(lines)


def run(rayshade, path, work, tag):
    stats = os.path.join(work, tag + ".stats")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([rayshade, "-q", "-t", "1", "-V", stats, "-O",
                    os.path.join(work, tag + ".png"), path], check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    c = chain.counters(stats)
    obj = "Implicit object 1: "
    evals = sum(c.get(obj + k, 0) for k in
                ("field evaluations", "gradient evaluations", "bound evaluations"))
    return {
        "cpu": (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime),
        "per_ray": evals / c["Total rays"],
        "per_call": evals / c[obj + "intersection calls"],
        "build": c.get(obj + "preprocessing time (microseconds)", 0) / 1e6,
    }


def instructions(rayshade, path, work, tag):
    """The instructions callgrind counts in one render of `path` (its output's summary)."""
    out = os.path.join(work, tag + ".callgrind")
    subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out, rayshade,
                    "-q", "-t", "1", "-O", os.path.join(work, tag + ".cg.png"), path],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(out) as f:
        for line in f:
            if line.startswith("summary:"):
                return int(line.split()[1])
    raise RuntimeError("no summary in " + out)


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=os.path.join(root, "build"))
    ap.add_argument("--size", type=int, default=256, help="image side in pixels")
    ap.add_argument("--samples", type=int, default=3, help="samples per pixel side")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--callgrind", action="store_true",
                    help="also count each variant's instructions under callgrind")
    args = ap.parse_args()
    rayshade = os.path.join(args.build, "rayshade", "rayshade")
    points = chain.load_points(1000)
    runs = {"static": [], "blurred": []}
    with tempfile.TemporaryDirectory() as work:
        paths = {}
        for name in runs:
            paths[name] = os.path.join(work, name + ".ray")
            with open(paths[name], "w") as f:
                f.write(scene(points, args.size, args.samples, name == "blurred"))
        for _ in range(args.repeat):  # interleaved, so load changes hit both alike
            for name in runs:
                runs[name].append(run(rayshade, paths[name], work, name))
        counts = {name: instructions(rayshade, paths[name], work, name)
                  for name in runs} if args.callgrind else {}
    print("1,000-point chain, method patches, %dx%d, %d samples per pixel, 1 thread, "
          "median of %d runs" % (args.size, args.size, args.samples ** 2, args.repeat))
    print("%-8s %8s %9s %12s %13s" % ("variant", "cpu s", "build s", "evals/ray", "evals/call"))
    med = {}
    for name, rs in runs.items():
        cpu = statistics.median(r["cpu"] for r in rs)
        r = rs[0]  # the counters are deterministic
        med[name] = (cpu, r["per_ray"], r["per_call"])
        print("%-8s %8.2f %9.3f %12.1f %13.1f" % (name, cpu, r["build"], r["per_ray"],
                                                  r["per_call"]))
    b, s = med["blurred"], med["static"]
    print("ratio blurred/static: cpu time %.2f (target within 2x), evaluations per ray %.2f, "
          "per intersection call %.2f" % (b[0] / s[0], b[1] / s[1], b[2] / s[2]))
    if counts:
        print("callgrind instructions: static %.3f G, blurred %.3f G, ratio %.3f" %
              (counts["static"] / 1e9, counts["blurred"] / 1e9,
               counts["blurred"] / counts["static"]))


if __name__ == "__main__":
    main()

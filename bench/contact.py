#!/usr/bin/env python3
"""Cost of deformed implicit patches against undeformed ones (issue 5), on the figure-7 scene.

Renders examples/implicit/fig7.ray twice with one thread: as written (the capsule a1 in
contact with the blob b1 + b2: two patches deformed, each with its own octree on the deformed
field) and with its `contact` and `propagation` lines removed (the same skeletons, not
blending, undeformed: a union with a crease). The yellow wire boxes are removed from both, so
only the implicit object differs. For each variant it reports the median over --repeat runs
of the rendering wall time, and the implicit object's counters from `rayshade -v`: field
evaluations, and field + gradient + bound evaluations, per intersection call (per ray tested
against the object; the deformed field's opponent evaluations count as field evaluations of
their own). The ratios deformed / undeformed are printed last; the target is < 2.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile


def run(rayshade, scene, size, threads):
    image = os.path.join(os.path.dirname(scene), "image.png")
    out = subprocess.run([rayshade, "-v", "-t", str(threads), "-R", str(size), str(size),
                          "-O", image, scene], capture_output=True, text=True, check=True).stderr
    stats = {}
    for key, pattern in {
            "wall": r"Rendering wall time \(sec\):\s*([\d.]+)",
            "calls": r"Implicit object \d+: intersection calls:\s*(\d+)",
            "values": r"Implicit object \d+: field evaluations:\s*(\d+)",
            "gradients": r"Implicit object \d+: gradient evaluations:\s*(\d+)",
            "bounds": r"Implicit object \d+: bound evaluations:\s*(\d+)",
            "build": r"Implicit object \d+: preprocessing time \(microseconds\):\s*(\d+)"}.items():
        m = re.search(pattern, out)
        if not m:
            sys.exit("contact bench: no '%s' in rayshade -v output" % key)
        stats[key] = float(m.group(1))
    return stats


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=os.path.join(root, "build"))
    ap.add_argument("--size", type=int, default=512, help="image side in pixels")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--threads", type=int, default=1)
    args = ap.parse_args()
    rayshade = os.path.join(args.build, "rayshade", "rayshade")
    with open(os.path.join(root, "examples", "implicit", "fig7.ray")) as f:
        lines = [l for l in f if not re.match(r"\s*(cylinder|sphere) wire", l)]
    undeformed = [l for l in lines if not re.match(r"\s*(contact|propagation)\b", l)]
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, text in (("deformed", lines), ("undeformed", undeformed)):
            path = os.path.join(tmp, name + ".ray")
            with open(path, "w") as f:
                f.writelines(text)
            results[name] = path
        runs = {"deformed": [], "undeformed": []}
        for _ in range(args.repeat):  # interleaved, so load changes hit both alike
            for name in runs:
                runs[name].append(run(rayshade, results[name], args.size, args.threads))
    print("fig7 at %dx%d, %d thread(s), median of %d runs" %
          (args.size, args.size, args.threads, args.repeat))
    print("%-11s %9s %9s %12s %12s" % ("variant", "wall s", "build ms", "field/ray",
                                       "evals/ray"))
    med = {}
    for name, rs in runs.items():
        wall = statistics.median(r["wall"] for r in rs)
        build = statistics.median(r["build"] for r in rs) / 1000
        r = rs[0]  # counters are deterministic
        field = r["values"] / r["calls"]
        evals = (r["values"] + r["gradients"] + r["bounds"]) / r["calls"]
        med[name] = (wall, field, evals)
        print("%-11s %9.3f %9.2f %12.2f %12.2f" % (name, wall, build, field, evals))
    d, u = med["deformed"], med["undeformed"]
    print("ratio deformed/undeformed: time %.2f, field evaluations per ray %.2f, "
          "all evaluations per ray %.2f (target < 2)" % (d[0] / u[0], d[1] / u[1], d[2] / u[2]))


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Implicit fluids: N Gascuel point skeletons on a confined random walk, 100 to 1,000,000.

The scenes are the shared POV-Ray kit's snake chains scaled up (bench/implicit.py's walk:
points 0.6 apart, seed 1000 + N, confining cube sized so the chain's tube fills 5 % of it),
each point with Gascuel's linear kernel `field linear 0.45 2 1` (thickness 0.45, stiffness
2, radius 1, threshold 1), the kit's camera, lights and ground plane. Each is rendered by
rayshade at 512x512, `-S 1` (one sample per pixel), with the scene's default method and `-t
THREADS`. Printed per N: wall time, CPU time (user + system of that process alone) split
into the patches, hierarchy and lazy octree builds (the object's "preprocessing time"
counter: build CPU time summed over threads) and the rest (parsing, search, shading),
implicit evaluations per ray (field + gradient + bound, over every eye and shadow ray,
builds excluded), octree cells built and kept, octree memory and the process's peak resident
memory. The serial setup (parsing, the object's patches and hierarchy) is measured apart by
a render of one pixel on one thread (-R 1 1 -t 1: its CPU time), and the trace CPU per ray
is the frame's CPU time less the setup and less every lazy build (the object's
preprocessing counter), over the rays traced (eye and shadow: "Total rays"), in
microseconds; its ratio between the largest and smallest N is printed beside the whole
frame's. Then a sample of eye rays through random pixels is answered by rayquery with the
default method and with `-m exact` (the long-double ground truth): misses (exact hits,
default does not), false hits and the largest depth error, against the tolerance: once
without a footprint (the fixed 1e-7, and per-cell trees descend to their full depth) and
once with the pixel's footprint as the render's eye rays carry it (rayquery -f: the
automatic tolerance, at most 1e-6, and the coarse descent of per-cell trees).

With --blob the same table follows for the blob kernel (s = 1, R = 1, threshold 0.6, the
shared chains' field, on the kit's own chains where it has them) under `method patches`,
with POV-Ray's `blob` trace time on the same points, one thread, when `povray` is installed
(POV-Ray 3.7 refuses a blob of a million components: its columns are then nan).

Usage: bench/fluid.py [--build DIR] [--sizes 100,10000,100000,1000000] [--threads 2]
       [--rays 200] [--no-check] [--blob] [--no-povray] [--keep DIR]
Figures come from one run on a shared machine: compare ratios from the same run.
"""
import argparse
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import implicit as chains  # noqa: E402  (the shared walk, camera and POV-Ray runner)

REPO = os.path.dirname(HERE)
WIDTH = HEIGHT = 512
FOV = 45.0
TOLERANCE = 1e-7  # the fixed tolerance of `tolerance auto` on rays without a footprint
AUTO_TOLERANCE_CAP = 1e-6  # its largest value on rays with a footprint (lg_octree.h)
# The eye rays' footprint spread: a pixel's angular size on the axis (the camera's
# min(|dx|, |dy|)·cos θ/ℓ is at most this).
PIXEL_SPREAD = 2 * math.tan(math.radians(FOV / 2)) / WIDTH


def gascuel_scene(pts, plane=True):
    """The render scene; without the plane for the rayquery check, so every hit counted is
    the fluid's."""
    w = chains.view(pts)
    out = ["eyep %s\nlookp %s\nup 0 0 1\nfov %g\nscreen %d %d\n"
           % (chains.v3(w["eye"]), chains.v3(w["look"]), FOV, WIDTH, HEIGHT)]
    for pos, intensity in w["lights"]:
        out.append("light %g point %s\n" % (intensity, chains.v3(pos)))
    out.append("surface white ambient 0.02 0.02 0.02 diffuse 0.5 0.5 0.5 "
               "specular 0.8 0.8 0.8 specpow 32\n")
    if plane:
        out.append("plane white 0 0 %.6f 0 0 1\n" % w["plane"])
    out.append("implicit white\n field linear 0.45 2 1\n")
    out += [" point p%d %s\n" % (i, chains.v3(p)) for i, p in enumerate(pts)]
    out.append("end\n")
    return "".join(out)


# GNU time, when installed, reports its child's peak resident memory. wait4's own figure for
# a child of this script is not that: Linux starts a forked child's peak at this script's
# resident size (at a million points the script holds ~300 MB of points and scene text).
GNU_TIME = "/usr/bin/time" if os.access("/usr/bin/time", os.X_OK) else None


def render(binary, scene_path, work, tag, threads, extra=()):
    """One render in its own process; returns its figures (wait4 gives that child's CPU
    time, GNU time its peak resident memory)."""
    stats = os.path.join(work, tag + ".stats")
    peak_file = os.path.join(work, tag + ".peak")
    wrapper = [GNU_TIME, "-f", "%M", "-o", peak_file] if GNU_TIME else []
    start = time.monotonic()
    proc = subprocess.Popen(wrapper + [binary, "-q", "-S", "1", "-t", str(threads), "-V",
                                       stats, "-O", os.path.join(work, tag + ".png")] +
                            list(extra) + [scene_path])
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.monotonic() - start
    if status != 0:
        sys.exit("rayshade failed on %s (status %d)" % (scene_path, status))
    peak_kib = usage.ru_maxrss
    if GNU_TIME:
        with open(peak_file) as fh:
            peak_kib = int(fh.read().split()[-1])
    c = chains.counters(stats)
    obj = "Implicit object 1: "
    rays = c.get("Total rays", 0)
    evals = sum(c.get(obj + k, 0) for k in
                ("field evaluations", "gradient evaluations", "bound evaluations"))
    cpu = usage.ru_utime + usage.ru_stime
    build = c.get(obj + "preprocessing time (microseconds)", 0) / 1e6
    return {
        "wall": wall, "cpu": cpu, "build": build, "rest": cpu - build,
        "evals": evals / rays if rays else float("nan"),
        "built": c.get(obj + "octree cells built", 0),
        "kept": c.get(obj + "octree cells", 0),
        "octree": c.get(obj + "octree memory (bytes)", 0) / 2 ** 20,
        "peak": peak_kib / 1024.0,
        "rays": rays,
    }


def setup_cpu(binary, scene_path, work, tag):
    """CPU seconds of the serial setup (parsing, the object's patches and hierarchy): a
    one-pixel render on one thread. Also returns the part of it the object counted as
    preprocessing (its patches, hierarchy and the few lazy builds of that render's rays)."""
    r = render(binary, scene_path, work, tag + "_setup", 1, ["-R", "1", "1"])
    return r["cpu"], r["build"]


def trace_per_ray(r, setup, setup_build):
    """Microseconds of trace CPU per ray: the frame's CPU less the setup outside the object
    (parsing: setup - setup_build) and less the object's whole preprocessing counter (its
    patches and hierarchy and every lazy build), over the rays traced."""
    trace = r["cpu"] - (setup - setup_build) - r["build"]
    return 1e6 * trace / r["rays"] if r["rays"] else float("nan")


def eye_rays(pts, count, seed):
    """World-space eye rays through random points of random pixels of the scene's camera
    (Rayshade's pinhole: fov is the horizontal angle, square pixels)."""
    w = chains.view(pts)
    eye, look = w["eye"], w["look"]
    forward = chains.unit([look[i] - eye[i] for i in range(3)])
    up = [0.0, 0.0, 1.0]
    right = chains.unit([forward[1] * up[2] - forward[2] * up[1],
                         forward[2] * up[0] - forward[0] * up[2],
                         forward[0] * up[1] - forward[1] * up[0]])
    true_up = [right[1] * forward[2] - right[2] * forward[1],
               right[2] * forward[0] - right[0] * forward[2],
               right[0] * forward[1] - right[1] * forward[0]]
    half = math.tan(math.radians(FOV / 2))
    rng = random.Random(seed)
    rays = []
    for _ in range(count):
        x = (2 * (rng.randrange(WIDTH) + rng.random()) / WIDTH - 1) * half
        y = (2 * (rng.randrange(HEIGHT) + rng.random()) / HEIGHT - 1) * half * HEIGHT / WIDTH
        d = chains.unit([forward[i] + x * right[i] + y * true_up[i] for i in range(3)])
        rays.append("%r %r %r %r %r %r" % (eye[0], eye[1], eye[2], d[0], d[1], d[2]))
    return rays


def query(rayquery, scene_path, rays, extra):
    out = subprocess.run([rayquery] + extra + [scene_path], input="\n".join(rays) + "\n",
                         capture_output=True, text=True, check=True).stdout.split("\n")
    return [float(line.split()[1]) if line.startswith("hit") else None
            for line in out if line.strip()]


def check(rayquery, scene_path, pts, count, extra):
    """Misses, false hits, the largest depth error and the exact hits of the default method
    (with `extra` options) against -m exact."""
    rays = eye_rays(pts, count, 7 + len(pts))
    got = query(rayquery, scene_path, rays, extra)
    want = query(rayquery, scene_path, rays, ["-m", "exact"])
    misses = sum(1 for g, e in zip(got, want) if e is not None and g is None)
    false_hits = sum(1 for g, e in zip(got, want) if e is None and g is not None)
    errors = [abs(g - e) for g, e in zip(got, want) if e is not None and g is not None]
    return misses, false_hits, max(errors) if errors else 0.0, sum(e is not None for e in want)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--sizes", default="100,10000,100000,1000000")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--rays", type=int, default=200, help="eye rays checked against exact")
    ap.add_argument("--no-check", action="store_true", help="skip the rayquery comparison")
    ap.add_argument("--blob", action="store_true", help="also the blob kernel, method patches")
    ap.add_argument("--no-povray", action="store_true")
    ap.add_argument("--keep", help="keep scenes and images in this folder")
    args = ap.parse_args()
    binary = os.path.join(args.build, "rayshade", "rayshade")
    rayquery = os.path.join(args.build, "rayquery", "rayquery")
    for program in (binary, rayquery):
        if not os.access(program, os.X_OK):
            sys.exit("build the programs first (%s)" % program)
    work = args.keep or tempfile.mkdtemp(prefix="fluid-bench-")
    os.makedirs(work, exist_ok=True)
    sizes = [int(x) for x in args.sizes.split(",")]
    try:
        print("Gascuel linear kernel e=0.45 k=2 R=1, T=1; 512x512, -S 1, %d thread(s), "
              "default method" % args.threads)
        print("| points | wall s | CPU s | build CPU s | rest CPU s | setup CPU s | trace µs/ray |"
              " evals/ray | cells built |"
              " cells kept | octree MiB | peak MiB | check: rays hit | misses | false hits |"
              " max depth error | with footprint: misses | false hits | max depth error |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        per_frame, per_ray = {}, {}
        for n in sizes:
            pts = chains.walk(n, 1000 + n)
            path = os.path.join(work, "fluid_%d.ray" % n)
            with open(path, "w") as fh:
                fh.write(gascuel_scene(pts))
            r = render(binary, path, work, "fluid_%d" % n, args.threads)
            setup, setup_build = setup_cpu(binary, path, work, "fluid_%d" % n)
            per_frame[n] = r["cpu"]
            per_ray[n] = trace_per_ray(r, setup, setup_build)
            if args.no_check:
                agreement = "| - | - | - | - | - | - | - |"
            else:
                bare = os.path.join(work, "fluid_%d_check.ray" % n)
                with open(bare, "w") as fh:
                    fh.write(gascuel_scene(pts, plane=False))
                misses, false_hits, worst, hits = check(rayquery, bare, pts, args.rays, [])
                fmisses, ffalse, fworst, _ = check(rayquery, bare, pts, args.rays,
                                                   ["-f", repr(PIXEL_SPREAD)])
                agreement = "| %d/%d | %d | %d | %.1e (tol %.0e) | %d | %d | %.1e (tol <= %.0e) |" % (
                    hits, args.rays, misses, false_hits, worst, TOLERANCE, fmisses, ffalse,
                    fworst, AUTO_TOLERANCE_CAP)
            print("| %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f | %d | %d | %.1f | %.0f %s"
                  % (n, r["wall"], r["cpu"], r["build"], r["rest"], setup, per_ray[n],
                     r["evals"], r["built"], r["kept"], r["octree"], r["peak"], agreement),
                  flush=True)
        if len(sizes) > 1:
            print("CPU per frame (about the same rays at every N), largest / smallest N: %.2f"
                  % (per_frame[sizes[-1]] / per_frame[sizes[0]]))
            print("Trace CPU per ray (setup and lazy builds excluded), largest / smallest N: "
                  "%.2f" % (per_ray[sizes[-1]] / per_ray[sizes[0]]))
        if args.blob:
            pov = not args.no_povray and shutil.which("povray")
            print()
            print("Blob kernel s=1 R=1, T=0.6, method patches, %d thread(s); POV-Ray blob on "
                  "the same points, one thread (its CPU time is the fair comparison)"
                  % args.threads)
            print("| points | wall s | CPU s | build CPU s | evals/ray | peak MiB |"
                  " POV trace s | POV CPU s | CPU / POV CPU |")
            print("|---|---|---|---|---|---|---|---|---|")
            for n in sizes:
                pts = chains.walk(n, 1000 + n) if n > 10000 else chains.load_points(n)
                path = os.path.join(work, "blob_%d.ray" % n)
                with open(path, "w") as fh:
                    fh.write(chains.rayshade_scene(pts, "patches"))
                r = render(binary, path, work, "blob_%d" % n, args.threads)
                trace = traceCpu = float("nan")
                if pov:
                    trace, traceCpu = chains.run_povray(chains.pov_scene(pts), work,
                                                        "blob_%d" % n)
                print("| %d | %.2f | %.2f | %.2f | %.1f | %.0f | %.2f | %.2f | %.2f |"
                      % (n, r["wall"], r["cpu"], r["build"], r["evals"], r["peak"], trace,
                         traceCpu, chains.ratio(r["cpu"], traceCpu)), flush=True)
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()

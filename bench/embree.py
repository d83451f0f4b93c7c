#!/usr/bin/env python3
"""Embree 3 against our own ray tracing on the SPD scenes (issue 15's evaluation).

For each scene's list file (everything in the top-level list, which our automatic
hierarchy accelerates; bench/spd/ in the shared kit), interleaved, single-threaded:
  - embree_eval (bench/embree/embree_eval.cpp, -DRAYSHADE_EMBREE_EVAL=ON): Embree's build
    and its trace of one eye ray per pixel (single rays and packets of 8) and one shadow
    ray per eye hit and point light, in CPU seconds;
  - our rayshade on the same file: setup (the CPU seconds of `-R 1 1`) and render (whole
    minus setup), with the rays it cast (`-V`: eye, shadow and any reflected rays), so the
    cost per ray compares like with like; ours shade every hit too (Embree's figures are
    traversal and intersection only);
  - precision: every 64th eye ray traced by both Embree (single precision, default and
    robust builds) and our rayquery (doubles): rays one hits and the other misses, and the
    largest and median relative difference of the hit distance.
Scenes whose primitives Embree lacks (tree's cones) or that the evaluator cannot triangulate
faithfully (gears' non-convex outlines) are reported as not evaluated.
"""
import argparse
import gzip
import os
import resource
import statistics
import subprocess
import sys
import tempfile


def cpu_of(cmd, **kw):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.run(cmd, capture_output=True, text=True, **kw)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return proc, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def embree(tool, scene, rays, robust):
    cmd = [tool] + (["--robust"] if robust else []) + ["--rays", rays, scene]
    proc, _ = cpu_of(cmd)
    if proc.returncode != 0:
        return None, proc.stderr.strip()
    line = [l for l in proc.stdout.splitlines() if l.startswith("figures ")][0].split()
    f = dict(zip(line[1::2], map(float, line[2::2])))
    return f, None


def ours(rayshade, scene, work):
    stats = os.path.join(work, "stats")
    out = os.path.join(work, "ours.png")
    _, setup = cpu_of([rayshade, "-q", "-t", "1", "-R", "1", "1", "-O", out, scene], check=True)
    _, whole = cpu_of([rayshade, "-q", "-t", "1", "-V", stats, "-O", out, scene], check=True)
    rays = 0
    for line in open(stats):
        if line.startswith("Total rays:"):
            rays = int(line.split()[-1])
    return setup, whole - setup, rays


def precision(rayquery, scene, rays):
    queries = [l.split() for l in open(rays)]
    answer = subprocess.run([rayquery, scene], input="".join(" ".join(q[:6]) + "\n"
                                                              for q in queries),
                            capture_output=True, text=True, check=True).stdout.split("\n")
    disagree, rel = 0, []
    for q, a in zip(queries, answer):
        a = a.split()
        theirs_hit, ours_hit = q[6] == "hit", a[0] == "hit"
        if theirs_hit != ours_hit:
            disagree += 1
        elif ours_hit:
            t_ours, t_theirs = float(a[1]), float(q[7])
            rel.append(abs(t_theirs - t_ours) / t_ours)
    return len(queries), disagree, max(rel) if rel else 0.0, statistics.median(rel) if rel else 0.0


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=os.path.join(root, "build"))
    ap.add_argument("--kit", default=os.path.join(root, "..", "shared", "bench", "spd", "scenes"))
    ap.add_argument("--rounds", type=int, default=2, help="minimum over this many rounds")
    ap.add_argument("scenes", nargs="*",
                    default=["balls", "gears", "mount", "teapot", "tetra", "tree"])
    args = ap.parse_args()
    tool = os.path.join(args.build, "bench", "embree", "embree_eval")
    rayshade = os.path.join(args.build, "rayshade", "rayshade")
    rayquery = os.path.join(args.build, "rayquery", "rayquery")
    if not os.path.exists(tool):
        sys.exit("embree.py: %s missing: configure with -DRAYSHADE_EMBREE_EVAL=ON "
                 "(apt-get install libembree-dev)" % tool)
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for name in args.scenes:
            scene = os.path.join(work, name + ".ray")
            with gzip.open(os.path.join(args.kit, name + ".ray.gz"), "rt") as f, \
                    open(scene, "w") as g:
                g.write(f.read())
            rays = os.path.join(work, name + ".rays")
            best_e, best_o, error = None, None, None
            for _ in range(args.rounds):  # interleaved rounds, minimum of each figure
                e, error = embree(tool, scene, rays, False)
                if e is None:
                    break
                o = ours(rayshade, scene, work)
                best_e = e if best_e is None else {k: min(v, best_e[k]) for k, v in e.items()}
                best_o = o if best_o is None else (min(o[0], best_o[0]), min(o[1], best_o[1]),
                                                   o[2])
            if best_e is None:
                rows.append((name, error))
                continue
            prec = precision(rayquery, scene, rays)
            embree(tool, scene, rays, True)
            prec_robust = precision(rayquery, scene, rays)
            rows.append((name, best_e, best_o, prec, prec_robust))
    print("SPD list files, 512x512, one thread, CPU seconds (minimum of %d interleaved rounds)"
          % args.rounds)
    print("| scene | Embree build | Embree eye (1 / packets of 8) | Embree shadow | Embree "
          "rays/s | our setup (parse + build) | our render (with shading) | our rays | "
          "our rays/s | checked rays | hit/miss disagreements (robust) | max rel. t diff "
          "(robust) | median rel. t diff |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for row in rows:
        if len(row) == 2:
            print("| %s | not evaluated: %s |" % row)
            continue
        name, e, o, p, pr = row
        trace = e["eye"] + e["shadow"]
        print("| %s | %.3f | %.3f / %.3f | %.3f | %.1fM | %.2f | %.2f | %.2fM | %.1fM | %d | "
              "%d (%d) | %.1e (%.1e) | %.1e |"
              % (name, e["build"], e["eye"], e["packet"], e["shadow"], e["rays"] / trace / 1e6,
                 o[0], o[1], o[2] / 1e6, o[2] / max(o[1], 1e-9) / 1e6, p[0], p[1], pr[1], p[2],
                 pr[2], p[3]))


if __name__ == "__main__":
    main()

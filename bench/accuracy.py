#!/usr/bin/env python3
"""Speed against accuracy of the implicit intersection methods, charted.

Chart 1 (docs/images/speed-accuracy.png): cost per ray against error, one curve per method
swept over its knob, on (a) random rays into skeleton scenes (a random-walk chain of blob
points as in bench/implicit.py, and a random-walk chain of quadratic-kernel segments) and
(b) the stability suite's rays (tests/stability/cases.py; not the cases with blend lists or
contacts, which only patches models: see models_beyond_plain_sum). Cost: EVALS per ray as printed
by rayquery (top row) and time per ray (bottom row: rayquery's CPU time with the rays minus
without them, so parsing and octree builds are excluded; rayquery is single-threaded, so
this is its wall time on an idle machine, and unlike wall time it is not stretched by other
jobs on a shared one). Error: the 99th percentile
of |t - t_ref| over rays that both hit, relative to the pixel footprint at the hit of a
512-pixel camera with a 30° field of view (footprint(t) = 2·t·tan(15°)/512 for a unit
direction, t floored at 1 so secondary rays starting on a surface are judged at the scene's
scale). t_ref: `-m exact` (the long-double ground truth) on (a), when this build has it,
else patches at tolerance 1e-12 (the summary says which); the analytic expectations on (b).
A hit farther than WRONG_ROOT from the reference is a wrong root (another surface sheet) and
counted as a rate, not in the percentile. Hollow markers: a miss, a false hit or a wrong root
occurred (rates in docs/speed-accuracy.md).

Chart 2 (docs/images/cost-vs-skeletons.png): cost per ray against skeleton count (random-walk
blob chains of 10 ... 10,000 points), each method at its default knob.

Methods are selected with the scene statements of the shared contract (`method M [Step]`,
`tolerance Eps`, `octree Depth`), so a method this build lacks makes the scene fail to parse
and is left out ("n/a"). The automatic tolerance mode (`-f SPREAD`) is plotted as one point
when rayquery accepts it.

A curve stops after a point that took more than POINT_BUDGET seconds to measure (its finer
knob values would take longer still); the markdown lists the points measured.

Usage: bench/accuracy.py [--build DIR] [--rays N] [--sizes 10,100,1000,10000] [--quick]
"""
import argparse
import math
import os
import random
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # no __pycache__ beside the sources
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests", "stability"))
import cases as stability_cases  # noqa: E402
import implicit as chain_bench  # noqa: E402
import raybench  # noqa: E402

PIXELS, FOV_DEGREES = 512, 30.0
SPREAD = 2 * math.tan(math.radians(FOV_DEGREES) / 2) / PIXELS  # footprint per unit distance
ERROR_FLOOR = 1e-12   # plotted in place of a zero p99 (log axis)
TOLERANCES = (1e-1, 1e-2, 1e-3, 1e-4, 1e-6, 1e-8)
STEPS = (0.4, 0.2, 0.1, 0.05, 0.02)
DEPTHS = (2, 4, 6, 8)
TIMEOUT = 300.0       # seconds per rayquery run; a method slower than that is left out
TIMED_RAYS = 10000    # queries per timing run
WRONG_ROOT = 0.25     # |t - t_ref| beyond this (object-space distance) is another surface
                      # sheet: above every tolerance swept (0.1), below the thinnest part
                      # of the random scenes (tubes of radius 0.2, so sheets 0.4 apart)
POINT_BUDGET = 60.0   # seconds: a sweep point slower than that ends its curve (finer knobs
                      # cost more; sphere tracing crawls to its step cap on grazing rays)

# (curve label, knob name, knob values, statements for a knob value)
SWEEPS = (
    ("patches", "tolerance", TOLERANCES, lambda v: ["method patches", "tolerance %g" % v]),
    ("patches (octree depth, tol 1e-6)", "max depth", DEPTHS,
     lambda v: ["method patches", "tolerance 1e-6", "octree %d" % v]),
    ("kb89", "tolerance", TOLERANCES, lambda v: ["method kb89", "tolerance %g" % v]),
    ("march (tol 1e-6)", "step", STEPS, lambda v: ["method march %g" % v, "tolerance 1e-6"]),
    ("sphere", "tolerance", TOLERANCES, lambda v: ["method sphere", "tolerance %g" % v]),
    ("segment", "tolerance", TOLERANCES, lambda v: ["method segment", "tolerance %g" % v]),
    ("polynomial (no knob)", "—", ("—",), lambda v: ["method polynomial"]),
)
DEFAULTS = (("patches", ["method patches"]), ("kb89", ["method kb89"]),
            ("march", ["method march"]), ("sphere", ["method sphere"]),
            ("segment", ["method segment"]), ("polynomial", ["method polynomial"]))


# --- scenes and rays -------------------------------------------------------------------

def implicit_block(header, skeleton_lines):
    return ("surface s diffuse 1 1 1\nname thing implicit s\n%s\n%send\nobject thing\n"
            % (header, "".join(skeleton_lines)))


def chain_scene(points):
    """bench/implicit.py's skeletons and kernel (blob s = 1, R = 1, threshold 0.6)."""
    return implicit_block(" threshold %g field blob %g %g" % (
        chain_bench.THRESHOLD, chain_bench.STRENGTH, chain_bench.RADIUS),
        [" point p%d %r %r %r\n" % ((i,) + tuple(p)) for i, p in enumerate(points)])


def segment_scene(points):
    """Consecutive walk points joined by segments; quadratic kernel e = 0.2, k = 5, R = 0.5
    (m = 1.5), so joints blend and the chain is a tube of radius about 0.2."""
    return implicit_block(" field quadratic 0.2 5 0.5",
                          [" segment s%d %r %r %r %r %r %r\n" % ((i,) + tuple(a) + tuple(b))
                           for i, (a, b) in enumerate(zip(points, points[1:]))])


def random_rays(points, count, seed, margin=1.0):
    """Rays from random points of a sphere around the skeletons' box towards random points
    inside the box (unit directions): most meet the surface, some graze or miss."""
    rng = random.Random(seed)
    lo = [min(p[i] for p in points) - margin for i in range(3)]
    hi = [max(p[i] for p in points) + margin for i in range(3)]
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    radius = 1.5 * math.dist(lo, hi)
    lines = []
    for _ in range(count):
        v = raybench.normalize([rng.gauss(0, 1) for _ in range(3)])
        o = [c + radius * x for c, x in zip(centre, v)]
        target = [rng.uniform(a, b) for a, b in zip(lo, hi)]
        d = raybench.normalize([b - a for a, b in zip(o, target)])
        lines.append("%r %r %r %r %r %r" % tuple(o + d))
    return lines


# --- measuring -------------------------------------------------------------------------

class Measure:
    """One method at one knob value on one ray set."""

    def __init__(self):
        self.evals = self.seconds = 0.0
        self.rays = self.hits_both = self.misses = self.false_hits = self.skipped = 0
        self.wrong_roots = 0
        self.relative_errors = []

    def add(self, answers, truths, seconds_per_ray):
        """answers: rayquery (hit, t, evals); truths: (hit, t) or None (no verdict)."""
        self.seconds += seconds_per_ray * len(answers)
        for (hit, t, evals), truth in zip(answers, truths):
            self.rays += 1
            self.evals += evals
            if truth is None:
                continue
            true_hit, true_t = truth
            if true_hit and not hit:
                self.misses += 1
            elif hit and not true_hit:
                self.false_hits += 1
            elif hit and abs(t - true_t) > WRONG_ROOT:
                self.wrong_roots += 1
            elif hit:
                self.hits_both += 1
                self.relative_errors.append(abs(t - true_t) / (SPREAD * max(true_t, 1.0)))

    def summary(self):
        errors = sorted(self.relative_errors)

        def pct(q):
            return errors[min(len(errors) - 1, int(q * len(errors)))] if errors else float("nan")
        n = max(self.rays, 1)
        return {"evals": self.evals / n, "us": 1e6 * self.seconds / n, "p50": pct(0.5),
                "p99": pct(0.99), "max": errors[-1] if errors else float("nan"),
                "miss": 100.0 * self.misses / n, "false": 100.0 * self.false_hits / n,
                "wrong": 100.0 * self.wrong_roots / n,
                "rays": self.rays, "skipped": self.skipped}


def query(rayquery, scene, rays, args=(), timed=True):
    """(answers, seconds per ray) or None when the scene or options are rejected or the run
    times out. The time per ray comes from a second run with the rays repeated up to
    TIMED_RAYS queries, minus a run without rays (parsing and octree builds), in CPU
    seconds, so process start-up noise is spread over many queries."""
    full = raybench.rayquery(rayquery, scene, rays, args, timeout=TIMEOUT)
    if full.status != 0 or not rays:
        return None
    answers = raybench.parse_answers(full.stdout)
    if not timed:
        return answers, float("nan")
    # A set that already took a second (sphere tracing crawling up to its step cap) is timed
    # by that run alone.
    repeat = 1 if full.cpu_seconds > 1.0 else max(1, TIMED_RAYS // len(rays))
    many = full if repeat == 1 else raybench.rayquery(rayquery, scene, rays * repeat, args,
                                                      timeout=TIMEOUT)
    empty = raybench.rayquery(rayquery, scene, [], args, timeout=TIMEOUT)
    spent = many.cpu_seconds - empty.cpu_seconds
    # Not positive: the queries cost less than the noise of the build (NaN: not plotted).
    return answers, spent / (repeat * len(rays)) if spent > 0 else float("nan")


def reference(rayquery, scene, rays):
    """Ground truth of random rays: -m exact when available, else patches at 1e-12."""
    got = query(rayquery, raybench.with_implicit_statements(scene, ["method exact"]), rays,
                timed=False)
    label = "exact"
    if got is None:
        label = "patches, tolerance 1e-12"
        got = query(rayquery, raybench.with_implicit_statements(
            scene, ["method patches", "tolerance 1e-12"]), rays, timed=False)
    return [(hit, t) for hit, t, _ in got[0]], label


def models_beyond_plain_sum(scene):
    """Whether a scene's surface is not the plain sum of its skeletons' fields (blend lists
    or contacts): every method but patches ignores those statements and so renders another
    surface by design. Such cases are scored in docs/stability.md, not charted, where their
    metre-sized "errors" would hide the intersection errors the chart is about."""
    words = {line.split()[0] for line in scene.splitlines() if line.split()}
    return bool(words & {"blend", "contact", "propagation"})


def stability_sets():
    """(scene, ray lines, truths) per stability case; truths as (hit, t) or None for the
    tangency policy's either-way rays."""
    sets = []
    for case in stability_cases.build():
        if case.scene is None or models_beyond_plain_sum(case.scene):
            continue
        truths = []
        for ray in case.rays:
            e = ray.expect
            if isinstance(e, stability_cases.Miss):
                truths.append((False, None))
            elif isinstance(e, stability_cases.Hit):
                truths.append((True, e.t * math.sqrt(sum(x * x for x in ray.d))))
            else:
                truths.append(None)
        sets.append((case.scene, [r.line() for r in case.rays], truths))
    return sets


def unit_t(answers, lines):
    """Answers with t converted to distance (stability rays have non-unit directions)."""
    out = []
    for (hit, t, evals), line in zip(answers, lines):
        d = [float(x) for x in line.split()[3:6]]
        out.append((hit, None if t is None else t * math.sqrt(sum(x * x for x in d)), evals))
    return out


def sweep(rayquery, sets, statements, extra_args=()):
    """A Measure over the (scene, rays, truths) of a set that the method accepts (the
    others are counted in `skipped`: e.g. the polynomial method takes blob kernels only),
    or None if it accepts none."""
    m = Measure()
    for scene, rays, truths in sets:
        got = query(rayquery, raybench.with_implicit_statements(scene, statements), rays,
                    extra_args)
        if got is None:
            m.skipped += 1
            continue
        m.add(unit_t(got[0], rays), truths, got[1])
    return m if m.skipped < len(sets) else None


def chart_points(rayquery, sets, auto):
    """{curve: [(knob value, summary)]} for every sweep that this build supports."""
    curves = {}
    for label, _, values, make in SWEEPS:
        for v in values:
            start = time.monotonic()
            m = sweep(rayquery, sets, make(v))
            print("  %-34s %-8s %s" % (label, v, "n/a" if m is None else fmt_summary(m)),
                  flush=True)
            if m is None:
                break
            curves.setdefault(label, []).append((v, m.summary()))
            if time.monotonic() - start > POINT_BUDGET:
                break  # the finer knob values would cost more still

    if auto:
        m = sweep(rayquery, sets, ["method patches"], ("-f", repr(SPREAD)))
        if m is not None:
            curves["patches auto (-f)"] = [("auto", m.summary())]
    return curves


def fmt_summary(m):
    s = m.summary()
    return "evals %.1f  %.2f us  p99 %.3g px  miss %.2f%%  false %.2f%%  wrong %.2f%%" % (
        s["evals"], s["us"], s["p99"], s["miss"], s["false"], s["wrong"])


# --- output ----------------------------------------------------------------------------

def plot_chart1(panels, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, len(panels), figsize=(6.5 * len(panels), 10), squeeze=False)
    colours = {}
    for col, (title, curves) in enumerate(panels):
        for row, (key, xlabel) in enumerate((("evals", "evaluations per ray (EVALS)"),
                                              ("us", "time per ray (µs, CPU)"))):
            ax = axes[row][col]
            for label, points in curves.items():
                colour = colours.setdefault(label, "C%d" % (len(colours) % 10))
                xs = [max(s[key], 1e-3) for _, s in points]
                ys = [max(s["p99"], ERROR_FLOOR) if s["p99"] == s["p99"] else ERROR_FLOOR
                      for _, s in points]
                ax.plot(xs, ys, "-", color=colour, label=label)
                for (v, s), x, y in zip(points, xs, ys):
                    bad = s["miss"] > 0 or s["false"] > 0 or s["wrong"] > 0
                    ax.plot([x], [y], "o", color=colour, markersize=7,
                            markerfacecolor="white" if bad else colour)
                    ax.annotate(str(v), (x, y), fontsize=6, xytext=(3, 3),
                                textcoords="offset points")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel(xlabel)
            ax.set_ylabel("p99 |t − t_ref| / pixel footprint")
            ax.set_title(title, fontsize=10)
            ax.grid(True, which="both", alpha=0.3)
    axes[0][0].legend(fontsize=7)
    fig.suptitle("Cost against accuracy (512 px, 30° fov; hollow: misses, false hits or "
                 "wrong roots)")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def plot_chart2(rows, sizes, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    for ax, key, ylabel in ((axes[0], "evals", "evaluations per ray"),
                            (axes[1], "us", "time per ray (µs, CPU)")):
        for label, by_size in rows.items():
            ns = [n for n in sizes if n in by_size]
            ax.plot(ns, [max(by_size[n][key], 1e-3) for n in ns], "o-", label=label)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("skeletons (random-walk blob chain)")
        ax.set_ylabel(ylabel)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle("Cost per ray against skeleton count (default knobs)")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def markdown(panels, rows, sizes, ref_label, args):
    out = ["# Speed against accuracy", "",
           "Generated by `bench/accuracy.sh` (what is measured: the docstring of "
           "`bench/accuracy.py`). Error: the 99th percentile of |t − t_ref| over rays that "
           "both hit the same sheet (|t − t_ref| ≤ %g; farther is a wrong root), in pixel "
           "footprints of a 512-pixel camera with a 30° field of view "
           "(footprint 2·t·tan 15°/512 = %.3g·t). Reference on random rays: %s; on the "
           "stability rays: the analytic answers. %d random rays per scene." %
           (WRONG_ROOT, SPREAD, ref_label, args.rays), "",
           "![cost against error](images/speed-accuracy.png)", "",
           "![cost against skeleton count](images/cost-vs-skeletons.png)", ""]
    for title, curves in panels:
        out += ["## " + title, "",
                "| method | knob | evals/ray | µs/ray | p50 (px) | p99 (px) | max (px) | "
                "miss % | false hit % | wrong root % | rays (scenes rejected) |",
                "|---|---|---|---|---|---|---|---|---|---|---|"]
        for label, points in curves.items():
            for v, s in points:
                out.append("| %s | %s | %.1f | %.2f | %.2g | %.2g | %.2g | %.2f | %.2f | %.2f "
                           "| %d%s |"
                           % (label, v, s["evals"], s["us"], s["p50"], s["p99"], s["max"],
                              s["miss"], s["false"], s["wrong"], s["rays"],
                              " (%d)" % s["skipped"] if s["skipped"] else ""))
        absent = [label for label, *_ in SWEEPS if label not in curves]
        if absent:
            out.append("")
            out.append("Not in this build (scene rejected): " + ", ".join(absent) + ".")
        out.append("")
    out += ["## Cost against skeleton count", "",
            "| method | " + " | ".join("N = %d" % n for n in sizes) + " |",
            "|---|" + "---|" * len(sizes)]
    for label, by_size in rows.items():
        cells = [("%.1f evals, %.1f µs" % (by_size[n]["evals"], by_size[n]["us"])
                  if by_size[n]["us"] == by_size[n]["us"] else
                  "%.1f evals, time below the build's noise" % by_size[n]["evals"])
                 if n in by_size else "—" for n in sizes]
        out.append("| %s | %s |" % (label, " | ".join(cells)))
    out += ["", "— : not run (the method is absent, or took more than %d s at a smaller N)."
            % POINT_BUDGET]
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(raybench.REPO, "build"))
    ap.add_argument("--rays", type=int, default=2000, help="random rays per scene")
    ap.add_argument("--sizes", default="10,100,1000,10000")
    ap.add_argument("--docs", default=os.path.join(raybench.REPO, "docs"))
    args = ap.parse_args()
    rayquery = raybench.binaries(args.build)["rayquery"]
    auto = raybench.accepts(rayquery, ("-f", repr(SPREAD)))

    chain_points = chain_bench.walk(100, 7)
    segment_points = chain_bench.walk(41, 8)
    random_set = []
    for scene, points, seed in ((chain_scene(chain_points), chain_points, 1),
                                (segment_scene(segment_points), segment_points, 2)):
        rays = random_rays(points, args.rays, seed)
        truths, ref_label = reference(rayquery, scene, rays)
        random_set.append((scene, rays, truths))
    print("(a) random rays (reference: %s)" % ref_label, flush=True)
    panel_a = chart_points(rayquery, random_set, auto)
    print("(b) stability rays", flush=True)
    panel_b = chart_points(rayquery, stability_sets(), auto)
    panels = [("(a) random rays: blob chain of 100 points + chain of 40 segments", panel_a),
              ("(b) stability suite rays (analytic answers)", panel_b)]

    sizes = [int(n) for n in args.sizes.split(",")]
    rows, stopped = {}, set()
    for n in sizes:
        points = chain_bench.load_points(n)
        scene = chain_scene(points)
        rays = random_rays(points, min(args.rays, 1000), 100 + n)
        for label, statements in DEFAULTS:
            if label in stopped:
                continue
            start = time.monotonic()
            got = query(rayquery, raybench.with_implicit_statements(scene, statements), rays)
            if got is None:
                stopped.add(label)  # absent, or too slow: larger N would be slower still
                print("  N = %-6d %-10s n/a or timed out" % (n, label), flush=True)
                continue
            if time.monotonic() - start > POINT_BUDGET:
                stopped.add(label)
            answers, seconds = got
            s = {"evals": sum(e for _, _, e in answers) / len(answers), "us": 1e6 * seconds}
            rows.setdefault(label, {})[n] = s
            print("  N = %-6d %-10s %.1f evals  %.2f us" % (n, label, s["evals"], s["us"]),
                  flush=True)

    images = os.path.join(args.docs, "images")
    os.makedirs(images, exist_ok=True)
    plot_chart1(panels, os.path.join(images, "speed-accuracy.png"))
    plot_chart2(rows, sizes, os.path.join(images, "cost-vs-skeletons.png"))
    raybench.write_with_commentary(os.path.join(args.docs, "speed-accuracy.md"),
                                   markdown(panels, rows, sizes, ref_label, args))
    print("wrote docs/speed-accuracy.md and docs/images/{speed-accuracy,cost-vs-skeletons}.png")


if __name__ == "__main__":
    main()

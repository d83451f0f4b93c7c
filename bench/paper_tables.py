#!/usr/bin/env python3
"""The tables of Gascuel's "Implicit Patches" (1995, §3.2-3.3) on our test set.

Test set: the paper-figure scenes examples/implicit/fig3a, fig3b, fig5a, fig5b, fig6 and the
100-point blob chain of bench/implicit.py, each rendered at 320x240, one sample per pixel,
shadows on, one thread.

Table 1 (the paper's depth table): for maximum octree depth 0..10 (min depth 3, the paper's
setting), for `method kb89` and for `method patches` with Dratio -1 and 2 (scene statements
`octree D R` and `method M` appended to every implicit block): preprocessing time (octree
builds, the per-object counter of rayshade -v), rendering time (the process's CPU time minus
preprocessing: one thread, and CPU time is not stretched by other jobs on a shared machine),
octree memory (per-object counter) and the largest peak RSS of a render. Times are medians
of --reps renders per scene, summed over the test set, like the paper's sums.

Table 2 (heuristic 1bis and test 2bis): rayquery on the eye rays of the same scenes (one per
pixel, 320x240), default settings, with `-H NAME=off` switches: preprocessing (CPU time of
the octree rebuild the switches cause), query time (CPU time with the rays minus without),
evaluations per ray and octree memory, each compared with the row the switch departs from.
Besides 1bis and 2bis, the rows switch off our value-range test, which the paper did not
have and which prunes most of what 1bis would.
Rows whose switch rayquery does not accept read "needs -H".

Usage: bench/paper_tables.py [--build DIR] [--reps N] [--depths 0,1,...] [--out FILE]
"""
import argparse
import os
import sys
import tempfile

sys.dont_write_bytecode = True  # no __pycache__ beside the sources
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import implicit as chain_bench  # noqa: E402
import raybench  # noqa: E402

WIDTH, HEIGHT = 320, 240
CONFIGS = (("kb89", "kb89", "-1"), ("patches, Dratio −1", "patches", "-1"),
           ("patches, Dratio 2", "patches", "2"))
# (label, rayquery switches, the row it is compared with). Every row passes at least one
# switch, so every object is rebuilt once after parsing in every row ("1bis=on" is the
# default: a no-op that only forces that rebuild).
ALL_ON = "all on (default)"
RANGE_OFF = "value-range test off (the paper's build heuristics)"
SWITCHES = ((ALL_ON, ("-H", "1bis=on"), None),
            ("heuristic 1bis off", ("-H", "1bis=off"), ALL_ON),
            ("1bis in place of 1 (heuristic 1 off)", ("-H", "1=off"), ALL_ON),
            (RANGE_OFF, ("-H", "range=off"), None),
            ("range off, 1bis off", ("-H", "range=off", "-H", "1bis=off"), RANGE_OFF),
            ("range off, 1bis in place of 1", ("-H", "range=off", "-H", "1=off"), RANGE_OFF),
            ("test 2bis off", ("-H", "2bis=off"), ALL_ON))
PAPER_DEPTHS = (0, 2, 4, 5, 6, 7, 10)
PAPER = {  # Gascuel 1995, §3.2 table: preprocessing s, intersection s, memory Kb
    "kb89": ((0.62, 1.73, 50, 244, 710, None, None), (368, 302, 213, 167, 139, None, None),
             (529, 1220, 18770, 34820, 101770, None, None)),
    "new": ((0.7, 2.4, 37.5, 96, 365, 543, 8933), (369, 318, 204, 194, 177, 175, 140),
            (529, 1210, 5890, 13506, 9485, 12915, 268445)),
}


CHAIN_AND_FIGURES = ("fig3a", "fig3b", "fig5a", "fig5b", "fig6", "chain100")


def test_set():
    scenes = []
    for name in CHAIN_AND_FIGURES[:-1]:
        with open(os.path.join(raybench.REPO, "examples", "implicit", name + ".ray")) as fh:
            scenes.append((name, fh.read()))
    scenes.append(("chain100", chain_bench.rayshade_scene(chain_bench.load_points(100),
                                                          "patches")))
    return scenes


def render(rayshade, scene, work):
    path = os.path.join(work, "scene.ray")
    with open(path, "w") as fh:
        fh.write(scene)
    stats = os.path.join(work, "stats.txt")
    r = raybench.run([rayshade, "-q", "-v", "-t", "1", "-S", "1", "-R", str(WIDTH), str(HEIGHT),
                      "-V", stats, "-O", os.path.join(work, "out.png"), path])
    if r.status != 0:
        raise SystemExit("rayshade failed: " + r.stderr)
    with open(stats) as fh:
        c = raybench.counters(fh.read())
    pre = raybench.implicit_totals(c, "preprocessing time (microseconds)") / 1e6
    return {"pre": pre, "render": r.cpu_seconds - pre,
            "memory": raybench.implicit_totals(c, "octree memory (bytes)") / 1024,
            "rss": r.max_rss_kib / 1024}


def depth_table(rayshade, scenes, depths, reps, work):
    rows = {}
    for label, method, dratio in CONFIGS:
        for depth in depths:
            total = {"pre": 0.0, "render": 0.0, "memory": 0.0, "rss": 0.0}
            for _, text in scenes:
                scene = raybench.with_implicit_statements(
                    text, ["octree %d %s" % (depth, dratio), "method " + method])
                runs = [render(rayshade, scene, work) for _ in range(reps)]
                for key in ("pre", "render"):
                    total[key] += raybench.median([r[key] for r in runs])
                total["memory"] += runs[0]["memory"]
                total["rss"] = max(total["rss"], max(r["rss"] for r in runs))
            rows[(label, depth)] = total
            print("%-20s depth %2d: %s" % (label, depth, total), flush=True)
    return rows


def switch_table(rayquery, scenes, reps):
    rays = {}
    for name, text in scenes:
        cam = raybench.camera(text)
        rays[name] = raybench.eye_rays(cam["eyep"], cam["lookp"], cam["up"], cam["fov"][0],
                                       WIDTH, HEIGHT)
    declared = {}
    for name, text in scenes:
        runs = [raybench.rayquery(rayquery, text, [], verbose=True) for _ in range(reps)]
        c = raybench.counters(runs[0].stderr)
        declared[name] = {"cpu": raybench.median([r.cpu_seconds for r in runs]),
                          "memory": raybench.implicit_totals(c, "octree memory (bytes)")}
    rows = {}
    for label, args, _ in SWITCHES:
        if not raybench.accepts(rayquery, args):
            rows[label] = None
            print("%-40s needs -H" % label, flush=True)
            continue
        total = {"pre": 0.0, "query": 0.0, "evals": 0.0, "memory": 0.0, "rays": 0}
        for name, text in scenes:
            queries, empties, last = [], [], None
            for _ in range(reps):
                last = raybench.rayquery(rayquery, text, rays[name], args, verbose=True)
                empty = raybench.rayquery(rayquery, text, [], args)
                queries.append(last.cpu_seconds)
                empties.append(empty.cpu_seconds)
            # Every row rebuilds each object once after the build as declared: the rebuild's
            # CPU time is that of the run without rays less the declared scene's, and the
            # memory counter (summed over builds) less the declared build's.
            c = raybench.counters(last.stderr)
            total["pre"] += raybench.median(empties) - declared[name]["cpu"]
            total["query"] += raybench.median(queries) - raybench.median(empties)
            total["evals"] += sum(e for _, _, e in raybench.parse_answers(last.stdout))
            total["memory"] += (raybench.implicit_totals(c, "octree memory (bytes)") -
                                declared[name]["memory"]) / 1024
            total["rays"] += len(rays[name])
        rows[label] = total
        print("%-40s %s" % (label, total), flush=True)
    return rows


def fmt(x, digits=3):
    return "—" if x is None else ("%.*g" % (digits, x))


def markdown(depths, table1, table2, reps):
    out = ["# The paper's tables on our test set", "",
           "Generated by `bench/paper_tables.sh` (see bench/paper_tables.py for what is "
           "measured). Test set: the five paper-figure scenes of `examples/implicit/` and the "
           "100-point blob chain of `bench/implicit.py`, %dx%d, one sample per pixel, shadows "
           "on, one thread; times (CPU seconds) are medians of %d runs per scene, summed over "
           "the six scenes (the paper sums over its four images). Minimum octree depth 3 "
           "throughout, as in the paper." % (WIDTH, HEIGHT, reps), "",
           "## Table 1: cost by maximum octree depth", "",
           "| configuration | row | " + " | ".join(str(d) for d in depths) + " |",
           "|---|---|" + "---|" * len(depths)]
    for label, _, _ in CONFIGS:
        for key, name in (("pre", "preprocessing (s)"), ("render", "rendering CPU (s)"),
                          ("memory", "octree memory (KiB)"), ("rss", "peak RSS (MiB)")):
            out.append("| %s | %s | " % (label, name) +
                       " | ".join(fmt(table1[(label, d)][key]) for d in depths) + " |")
    out += ["", "The paper's table (its test set, 1995 hardware; `?`: memory exhausted):", "",
            "| | row | " + " | ".join(str(d) for d in PAPER_DEPTHS) + " |",
            "|---|---|" + "---|" * len(PAPER_DEPTHS)]
    for key, label in (("kb89", "KB89 (Dratio −1)"), ("new", "new (Dratio 2)")):
        for values, name in zip(PAPER[key], ("preproc. (s)", "inter. (s)", "memory (Kb)")):
            out.append("| %s | %s | " % (label, name) +
                       " | ".join("?" if v is None else str(v) for v in values) + " |")
    out += ["", "## Table 2: heuristic 1bis and test 2bis", "",
            "rayquery on one eye ray per pixel of each scene (%d rays in all), default settings "
            "(patches, max depth 6, Dratio 2), one switch at a time." %
            (len(CHAIN_AND_FIGURES) * WIDTH * HEIGHT), "",
            "| variant | preprocessing CPU (s) | query CPU (s) | evals/ray | octree memory (KiB) | "
            "compared with | preprocessing | query | evals | memory |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for label, _, against in SWITCHES:
        row = table2.get(label)
        if row is None:
            out.append("| %s | needs -H | | | | | | | | |" % label)
            continue
        base = table2.get(against) if against else None
        ratios = ["" if not base else fmt(row[k] / base[k]) if base[k] else "—"
                  for k in ("pre", "query", "evals", "memory")]
        out.append("| %s | %s | %s | %s | %s | %s | %s |" % (
            label, fmt(row["pre"]), fmt(row["query"]), fmt(row["evals"] / row["rays"]),
            fmt(row["memory"]), against or "", " | ".join(ratios)))
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(raybench.REPO, "build"))
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--depths", default=",".join(str(d) for d in range(11)))
    ap.add_argument("--out", default=os.path.join(raybench.REPO, "docs", "paper-tables.md"),
                    help="markdown file to write; text after the commentary marker is kept")
    args = ap.parse_args()
    bins = raybench.binaries(args.build)
    depths = [int(d) for d in args.depths.split(",")]
    scenes = test_set()
    with tempfile.TemporaryDirectory() as work:
        table1 = depth_table(bins["rayshade"], scenes, depths, args.reps, work)
    table2 = switch_table(bins["rayquery"], scenes, args.reps)
    raybench.write_with_commentary(args.out, markdown(depths, table1, table2, args.reps))
    print("wrote " + args.out)


if __name__ == "__main__":
    main()

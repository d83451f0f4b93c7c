#!/usr/bin/env python3
"""Runs the stability cases (cases.py) through rayquery, per intersection method.

  stability.py --rayquery BIN --case NAME [--methods patches]     one case; status 1 if a
                                                                  listed method fails it
  stability.py --rayquery BIN --markdown FILE [--methods all] [--require patches]
                                                                  the pass/fail table
  stability.py --list                 names of the cases that have a scene, one a line

A method that rayquery rejects (`-m NAME` exits with an error on a scene without implicit
objects) is "n/a" for every case; a case whose scene a method rejects is "n/a" for that
case (for example a kernel the method does not handle). Everything else is judged ray by ray against the
analytic expectations of cases.py. With --markdown the status is 0 unless a --require'd
method is unavailable or fails a case: methods that miss cases are expected failures,
recorded in the table.
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True  # no __pycache__ beside the sources
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cases as stability_cases  # noqa: E402

ALL_METHODS = ("auto", "patches", "kb89", "march", "sphere", "segment", "polynomial", "exact")
DEFAULT_METHOD = "patches"
SHOWN_FAILURES = 3  # failing rays listed per method and case in the markdown
PROBE_SCENE = stability_cases.SURFACE + "sphere s 1 0 0 0\n"  # no implicit object to reject


class Answer:
    """One output line of rayquery."""

    def __init__(self, words):
        self.hit = words[0] == "hit"
        if self.hit:
            self.t = float(words[1])
            self.p = tuple(map(float, words[2:5]))
            self.n = tuple(map(float, words[5:8]))
            self.object, self.patch = words[8], words[9]
            self.evals = int(words[10])
        else:
            self.evals = int(words[1])

    def describe(self):
        if not self.hit:
            return "miss (%d evals)" % self.evals
        return "hit t=%.17g n=(%.6g, %.6g, %.6g) patch %s (%d evals)" % (
            (self.t,) + self.n + (self.patch, self.evals))


class Run:
    """rayquery's answers to a list of rays, or why there are none."""

    def __init__(self, status, answers, error, seconds):
        self.status, self.answers, self.error, self.seconds = status, answers, error, seconds


def run_rayquery(binary, scene, ray_lines, args=(), workdir=None):
    """Writes the scene to a temporary file and feeds the rays (text lines) to rayquery."""
    with tempfile.TemporaryDirectory(dir=workdir) as tmp:
        path = os.path.join(tmp, "scene.ray")
        with open(path, "w") as fh:
            fh.write(scene)
        start = time.monotonic()
        proc = subprocess.run([binary] + list(args) + [path], input="\n".join(ray_lines) + "\n",
                              capture_output=True, text=True)
        seconds = time.monotonic() - start
    answers = [Answer(line.split()) for line in proc.stdout.splitlines() if line.strip()]
    return Run(proc.returncode, answers, proc.stderr.strip(), seconds)


def method_available(binary, method):
    return run_rayquery(binary, PROBE_SCENE, [], ("-m", method)).status == 0


def vector_error(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def judge(ray, answer):
    """(failure text or None, |Δt|·|d| of a hit that was expected, or None)."""
    expect = ray.expect
    if isinstance(expect, stability_cases.Miss):
        return (None if not answer.hit else "expected a miss, got " + answer.describe()), None
    if not answer.hit:
        if isinstance(expect, stability_cases.Either):
            return None, None
        return "expected hit t=%.17g, got %s" % (expect.t, answer.describe()), None
    length = math.sqrt(sum(x * x for x in ray.d))
    error = abs(answer.t - expect.t) * length
    if not all(math.isfinite(x) for x in answer.n + answer.p) or not math.isfinite(answer.t):
        return "non-finite hit: " + answer.describe(), error
    if abs(math.sqrt(sum(x * x for x in answer.n)) - 1) > 1e-9:
        return "normal not unit: " + answer.describe(), error
    if error > expect.allow:
        kind = "tangent point" if isinstance(expect, stability_cases.Either) else "hit"
        return ("expected %s t=%.17g ± %.3g, got %s (error %.3g)"
                % (kind, expect.t, expect.allow, answer.describe(), error)), error
    if isinstance(expect, stability_cases.Hit):
        verdicts = [surface_mismatch(answer, normal, patch, expect.normal_allow)
                    for normal, patch in [(expect.normal, expect.patch)] + expect.alternatives]
        if all(verdicts):
            return verdicts[0], error
    return None, error


def surface_mismatch(answer, normal, patch, normal_allow):
    """Why the hit's normal or patch is not the given one (None if it is). Methods without
    patches print '-' as the patch."""
    if normal is not None and vector_error(answer.n, normal) > normal_allow:
        return "expected normal (%.6g, %.6g, %.6g), got %s" % (normal + (answer.describe(),))
    if patch is not None and answer.patch != "-" and answer.patch != patch:
        return "expected patch %s, got %s" % (patch, answer.describe())
    return None


class Outcome:
    """A method's result on one case."""

    def __init__(self, state, failures=(), worst=None, evals=None, seconds=None, note=""):
        self.state, self.failures, self.worst = state, list(failures), worst
        self.evals, self.seconds, self.note = evals, seconds, note

    def cell(self):
        if self.state == "n/a":
            return "n/a"
        worst = "—" if self.worst is None else "%.1e" % self.worst
        if self.state == "pass":
            return "pass %s" % worst
        return "**FAIL** %d/%s, %s" % (len(self.failures), self.note, worst)


def run_case(binary, case, method):
    if case.scene is None:
        return Outcome("n/a", note=case.expectation)
    run = run_rayquery(binary, case.scene, [r.line() for r in case.rays],
                       ("-m", method))
    if run.status > 0 and not run.answers and method != DEFAULT_METHOD and \
            run_rayquery(binary, case.scene, [], ("-m", DEFAULT_METHOD)).status == 0:
        return Outcome("n/a", note="scene rejected: " + run.error.splitlines()[-1])
    failures, worst = [], None
    if run.status != 0:
        failures.append("rayquery exited with status %d: %s" % (run.status, run.error[-300:]))
    for i, ray in enumerate(case.rays):
        if i >= len(run.answers):
            failures.append("ray %d (%s): no answer" % (i, ray.label))
            continue
        failure, error = judge(ray, run.answers[i])
        if error is not None:
            worst = error if worst is None else max(worst, error)
        if failure:
            failures.append("ray %d (%s: %s): %s" % (i, ray.label, ray.line(), failure))
    evals = [a.evals for a in run.answers]
    return Outcome("fail" if failures else "pass", failures, worst,
                   sum(evals) / len(evals) if evals else None, run.seconds,
                   note=str(len(case.rays)))


def markdown(cases, methods, outcomes, available):
    out = ["# Stability suite: which intersection methods pass which case", "",
           "Generated by `tests/stability/stability.py --markdown docs/stability.md` "
           "(CTest runs every case for `%s`, the paper's method, and `auto`, the scene "
           "default: polynomial for blob-kernel points and segments that all blend, patches otherwise). "
           "Each case is a small scene "
           "with rays whose answers are known analytically (closed forms or one-dimensional "
           "solves of the kernel formula, `tests/stability/cases.py`). A cell gives pass or "
           "**FAIL** (failing rays / rays), then the worst hit-distance error measured "
           "(object-space distance; — when no hit was expected); n/a: the method does not "
           "exist in this build or rejects the case's scene. Scene tolerance %g; a hit passes "
           "within the tolerance plus the rounding of its inputs (cases.py, top)."
           % (DEFAULT_METHOD, stability_cases.TOLERANCE), "",
           "| case | category | what is expected | rays | " + " | ".join(methods) + " |",
           "|---|---|---|---|" + "---|" * len(methods)]
    for case in cases:
        row = [case.name, case.category, case.expectation,
               str(len(case.rays)) if case.rays else "—"]
        row += [outcomes[(case.name, m)].cell() for m in methods]
        out.append("| " + " | ".join(row) + " |")
    missing = [m for m in methods if not available[m]]
    if missing:
        out += ["", "Not available in this build: " + ", ".join(missing) + "."]
    listed = []
    for c in cases:
        for m in methods:
            failures = outcomes[(c.name, m)].failures
            listed += ["- `%s` / %s: %s" % (m, c.name, f) for f in failures[:SHOWN_FAILURES]]
            if len(failures) > SHOWN_FAILURES:
                listed.append("- `%s` / %s: … and %d more" %
                              (m, c.name, len(failures) - SHOWN_FAILURES))
    if listed:
        out += ["", "## Failing rays (the first %d per method and case)" % SHOWN_FAILURES, ""]
        out += listed
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rayquery", help="path of the rayquery binary")
    ap.add_argument("--methods", default=DEFAULT_METHOD,
                    help="comma-separated methods, or 'all' (%s)" % ",".join(ALL_METHODS))
    ap.add_argument("--case", help="run this case only")
    ap.add_argument("--markdown", help="write the table to this file")
    ap.add_argument("--require", action="append", default=[],
                    help="with --markdown: fail unless this method passes every case")
    ap.add_argument("--list", action="store_true", help="print the case names")
    args = ap.parse_args()
    cases = stability_cases.build()
    if args.list:
        print("\n".join(c.name for c in cases if c.scene is not None))
        return 0
    if not args.rayquery:
        ap.error("--rayquery is required")
    methods = list(ALL_METHODS) if args.methods == "all" else args.methods.split(",")
    if args.case:
        cases = [c for c in cases if c.name == args.case]
        if not cases:
            ap.error("no case named %r" % args.case)
    available = {m: method_available(args.rayquery, m) for m in methods}
    outcomes = {}
    for case in cases:
        for m in methods:
            outcome = run_case(args.rayquery, case, m) if available[m] else Outcome("n/a")
            outcomes[(case.name, m)] = outcome
            print("%-20s %-10s %s" % (case.name, m, outcome.cell()), flush=True)
            for failure in outcome.failures:
                print("    " + failure)
    if args.markdown:
        with open(args.markdown, "w") as fh:
            fh.write(markdown(cases, methods, outcomes, available))
        bad = [m for m in args.require
               if not available.get(m) or
               any(outcomes[(c.name, m)].state == "fail" for c in cases)]
        return 1 if bad else 0
    failed = any(o.state == "fail" for o in outcomes.values())
    unavailable = [m for m in methods if not available[m]]
    if unavailable:
        print("not available: " + ", ".join(unavailable))
    return 1 if failed or unavailable else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Checks of rayshade-farm (issue 16), on a real Slurm cluster or with local workers.

    farm_test.py --mode slurm|local --case NAME --farm FARM --rayshade RAYSHADE
                 --scenes DIR --work DIR

Every image the farm makes is compared byte for byte with the file a single rayshade run
writes from the same command line (same pixels, same PNG encoder). With --mode slurm the
commands find the test cluster through SLURM_CONF (tests/farm/slurm_cluster.py) and the
farm must use sbatch; with --mode local it must not.
"""

import argparse
import os
import shutil
import subprocess
import sys

ARGS = None
FAILURES = []


def check(condition, message):
    if not condition:
        FAILURES.append(message)
        print("FAIL: " + message)
    return condition


def farm(*args, env=None, expect=0):
    """Runs rayshade-farm; with Slurm, submit waits for the jobs. Returns the result."""
    words = list(args)
    if words[0] == "submit":
        words.insert(1, "--wait" if ARGS.mode == "slurm" else "--local")
    command = [sys.executable, ARGS.farm] + words
    env = dict(os.environ, **(env or {}))
    if ARGS.mode == "local":
        env.pop("SLURM_CONF", None)
    r = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env, cwd=ARGS.work)
    print(f"$ rayshade-farm {' '.join(words)}\n{r.stdout}(status {r.returncode})")
    if expect is not None:
        check(r.returncode == expect, f"rayshade-farm {words[0]} exited with {r.returncode}, expected {expect}")
    return r


def rayshade(*args):
    subprocess.run([ARGS.rayshade, "-q"] + list(args), check=True, cwd=ARGS.work)


def same_file(a, b):
    try:
        with open(a, "rb") as fa, open(b, "rb") as fb:
            return fa.read() == fb.read()
    except FileNotFoundError:
        return False


def scene(name):
    return os.path.join(ARGS.scenes, name)


def attempts(farm_dir, index):
    with open(os.path.join(farm_dir, "tasks", str(index), "log"), encoding="utf-8") as f:
        return [line for line in f if line.startswith("--- attempt") and ": " in line and "ended" not in line]


def fault_env(mode, match, always=False):
    return {"FAULT_RAYSHADE": ARGS.rayshade, "FAULT_MODE": mode, "FAULT_MATCH": match,
            "FAULT_MARKER": os.path.join(ARGS.work, "fault.marker"), "FAULT_ALWAYS": "1" if always else "0"}


FAULTY = os.path.join(os.path.dirname(os.path.abspath(__file__)), "faulty_rayshade.py")

# The still: a shared scene, small. Names with spaces and shell metacharacters throughout.
STILL = ["-R", "72", "54", "-S", "3"]
OUT = "still $(touch PWNED) 'q\" ;&.png"


def case_tiles():
    """2x2 and 3x1 tiles of a still equal a single-process render."""
    shutil.copy(scene("balls.ray"), os.path.join(ARGS.work, "balls scene;$x.ray"))
    rayshade(*STILL, "-O", "reference.png", "balls scene;$x.ray")
    for tiles in ("2x2", "3x1"):
        out = f"{tiles} {OUT}"
        farm("submit", "--tiles", tiles, "--", *STILL, "-O", out, "balls scene;$x.ray")
        check(same_file(os.path.join(ARGS.work, out), os.path.join(ARGS.work, "reference.png")),
              f"{tiles} tiles: the merged image differs from the single-process render")
    check(not os.path.exists(os.path.join(ARGS.work, "PWNED")), "a file name was run by a shell")


def case_frames():
    """Frames 0-7 of coin.ray in chunks of 3 (with 2x1 tiles, 2 CPUs per task, one task at a
    time) equal single-process frames."""
    common = ["-R", "40", "30", "-S", "2"]
    rayshade(*common, "-A", "0", "-N", "8", "-O", "ref.png", scene("coin.ray"))
    farm("submit", "--frames", "0-7", "--chunk", "3", "--tiles", "2x1", "--cpus-per-task", "2", "--max-running", "1",
         "--", *common, "-O", "coin.png", scene("coin.ray"))
    for f in range(8):
        check(same_file(os.path.join(ARGS.work, f"coin_f{f:03d}.png"), os.path.join(ARGS.work, f"ref_f{f:03d}.png")),
              f"frame {f} differs from the single-process render")
    # Chunks 0-2, 3-5, 6-7, two tiles each; each task renders with the CPUs it was given.
    fd = os.path.join(ARGS.work, "coin.png.farm")
    check(all(" -A 6 -N 2 " in attempts(fd, i)[0] and " -t 2 " in attempts(fd, i)[0] for i in (4, 5)),
          "the last chunk's tasks do not render frames 6-7 with 2 threads")


def case_fault():
    """A tile that fails once is retried, a tile stopped mid-render continues from its
    partial state; with --retries 0 the failure is reported and nothing is merged; a
    second submit then renders only the failed task."""
    rayshade(*STILL, "-O", "reference.png", scene("balls.ray"))
    # A tile (the second: x 36-71, y 0-26) fails once; the retry renders it.
    env = fault_env("fail", "-W 36 71 0 26")
    farm("submit", "--tiles", "2x2", "--rayshade", FAULTY, "--", *STILL, "-O", "retried.png", scene("balls.ray"), env=env)
    check(same_file(os.path.join(ARGS.work, "retried.png"), os.path.join(ARGS.work, "reference.png")),
          "after a retried tile the merged image differs")
    check(len(attempts(os.path.join(ARGS.work, "retried.png.farm"), 1)) == 2, "the failing tile did not run twice")
    os.remove(env["FAULT_MARKER"])

    # A tile stopped (SIGTERM, as Slurm stops a preempted task) mid-render continues from
    # its partial state with -c.
    big = ["-R", "160", "120", "-S", "4"]
    rayshade(*big, "-O", "big reference.png", scene("balls.ray"))
    env = fault_env("kill", "-W 80 159 0 119")
    farm("submit", "--tiles", "2x1", "--rayshade", FAULTY, "--", *big, "-O", "big killed.png", scene("balls.ray"),
         env=env)
    check(same_file(os.path.join(ARGS.work, "big killed.png"), os.path.join(ARGS.work, "big reference.png")),
          "after a stopped and continued tile the image differs")
    tries = attempts(os.path.join(ARGS.work, "big killed.png.farm"), 1)
    with open(os.path.join(ARGS.work, "big killed.png.farm", "tasks", "1", "log")) as f:
        saved = "partial state saved" in f.read()
    check(len(tries) == 2 and tries[1].rstrip().endswith(" -c") and saved,
          f"the stopped tile's second attempt did not continue from a saved state with -c: {tries}")
    os.remove(env["FAULT_MARKER"])

    # --retries 0: the failed tile is reported, the merge does not run, status says so.
    env = fault_env("fail", "-W 36 71 27 53", always=True)
    split = ["--tiles", "2x2", "--rayshade", FAULTY, "--retries", "0", "--"]
    out = farm("submit", *split, *STILL, "-O", "failed.png", scene("balls.ray"), env=env, expect=None)
    check(out.returncode != 0, "a failed task did not make submit fail")
    check(not os.path.exists(os.path.join(ARGS.work, "failed.png")), "an image was merged from incomplete tiles")
    status = farm("status", *split, *STILL, "-O", "failed.png", scene("balls.ray"), expect=1)
    check("task 3: failed" in status.stdout and "injected failure" in status.stdout,
          "status does not report the failed tile with its log")
    check("merge: not run" in status.stdout, "status does not say the merge did not run")
    # Submitted again without the fault: only the failed tile runs, then the merge.
    farm("submit", *split, *STILL, "-O", "failed.png", scene("balls.ray"), env=fault_env("fail", "no such arguments"))
    check(same_file(os.path.join(ARGS.work, "failed.png"), os.path.join(ARGS.work, "reference.png")),
          "the resubmitted farm's image differs")
    fd = os.path.join(ARGS.work, "failed.png.farm")
    check([len(attempts(fd, i)) for i in range(4)] == [1, 1, 1, 2],
          f"resubmission ran other tasks again: attempts {[len(attempts(fd, i)) for i in range(4)]}")


def case_resubmit():
    """A second submit of a finished farm submits and renders nothing."""
    args = ["--tiles", "2x1", "--", *STILL, "-O", "twice.png", scene("balls.ray")]
    farm("submit", *args)
    fd = os.path.join(ARGS.work, "twice.png.farm")
    before = os.stat(os.path.join(ARGS.work, "twice.png")).st_mtime_ns
    second = farm("submit", *args)
    check([len(attempts(fd, i)) for i in range(2)] == [1, 1], "the second submit rendered again")
    check(os.stat(os.path.join(ARGS.work, "twice.png")).st_mtime_ns == before, "the second submit merged again")
    if ARGS.mode == "slurm":
        check("nothing to submit" in second.stdout and "submitted" not in second.stdout,
              "the second submit sent jobs to Slurm")


def case_errors():
    """Bad input: one clear message, non-zero status, nothing submitted."""
    bad = os.path.join(ARGS.work, "bad scene.ray")
    with open(bad, "w") as f:
        f.write("sphere 1 0 0 0\nsphere oops\n")
    r = farm("submit", "--tiles", "2x2", "--", "-O", "bad.png", bad, expect=1)
    check(r.stdout.count("bad scene.ray:2") == 1, "the scene error is not reported exactly once with its line")
    check(not os.path.exists(os.path.join(ARGS.work, "bad.png.farm")), "a farm was set up for a broken scene")
    for split in (["--tiles", "0x2"], ["--tiles", "2by2"], ["--tiles", "100x1"], ["--frames", "5-2"],
                  ["--chunk", "0"], ["--retries", "-1"], ["--frobnicate"]):
        r = farm("submit", *split, "--", *STILL, "-O", "e.png", scene("balls.ray"), expect=1)
        check(split[0] in r.stdout, f"{split}: the message does not name the option")
    with open(os.path.join(ARGS.work, "a file"), "w") as f:
        f.write("x")
    r = farm("submit", "--farm-dir", os.path.join(ARGS.work, "a file", "farm"), "--", *STILL, "-O", "e.png",
             scene("balls.ray"), expect=1)
    check("cannot use the farm directory" in r.stdout, "an unusable farm directory is not reported")
    # A farm directory holding another render is not reused.
    farm("submit", "--", "-R", "8", "6", "-O", "small.png", scene("balls.ray"))
    r = farm("submit", "--", "-R", "8", "7", "-O", "small.png", scene("balls.ray"), expect=1)
    check("holds a different render" in r.stdout, "a farm directory of another render was reused")
    if ARGS.mode == "slurm":
        r = farm("submit", "--partition", "no-such-partition", "--", *STILL, "-O", "e.png", scene("balls.ray"),
                 expect=1)
        check("sbatch refused" in r.stdout, "sbatch's refusal is not reported")


def main():
    global ARGS
    p = argparse.ArgumentParser()
    for name in ("mode", "case", "farm", "rayshade", "scenes", "work"):
        p.add_argument("--" + name, required=True)
    ARGS = p.parse_args()
    ARGS.work = os.path.abspath(ARGS.work)
    shutil.rmtree(ARGS.work, ignore_errors=True)
    os.makedirs(ARGS.work)
    if ARGS.mode == "slurm" and (not os.environ.get("SLURM_CONF") or shutil.which("sbatch") is None):
        print("FAIL: the Slurm tests need sbatch and the test cluster (SLURM_CONF)")
        return 1
    globals()["case_" + ARGS.case]()
    if FAILURES:
        print(f"{len(FAILURES)} check(s) failed")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())

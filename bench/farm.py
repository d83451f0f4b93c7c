#!/usr/bin/env python3
"""Render-farm figures (issue 16), printed: see bench/farm.sh for usage.

1. Wall time of one scene (about 30 s on one core) rendered by one rayshade process on one
   core, by one process on every core, by 4 local farm tasks (2x2 tiles) and by 4 Slurm
   tasks on a single-node test cluster; each farm image is checked identical to the
   one-process image. CPU times are printed too (wall times on a shared machine are noisy).
2. The farm's own cost: the time from submit to the first task's start, and the overhead
   per task, measured with tasks that render almost nothing (2x1-pixel tiles): the farm's
   wall time times the number of tasks running at once, divided by the number of tasks.
3. The merge of a 4096x4096 image from 16 tiles of 1024x1024 (a rendered picture, as RGB
   mtv tiles and as RGBA PNG tiles), written as PNG.
"""

import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(command, **kw):
    """Wall seconds of `command`; its CPU seconds (and its children's) go to LAST_CPU."""
    global LAST_CPU
    start, cpu = time.perf_counter(), children_cpu()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, **kw)
    LAST_CPU = children_cpu() - cpu
    return time.perf_counter() - start


LAST_CPU = 0.0


def same(a, b):
    with open(a, "rb") as fa, open(b, "rb") as fb:
        return fa.read() == fb.read()


def first_start(farm_dir):
    starts = []
    for d in os.listdir(os.path.join(farm_dir, "tasks")):
        with open(os.path.join(farm_dir, "tasks", d, "status.json")) as f:
            starts.append(json.load(f)["started"])
    return min(starts)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--scene", default=os.path.join(ROOT, "..", "shared", "scenes", "rayshade", "glass.ray"))
    p.add_argument("--resolution", default="1800x1350", help="WxH of the timed render (default: ~30 s on one core)")
    p.add_argument("--no-slurm", action="store_true", help="leave out the Slurm figures")
    args = p.parse_args()
    rayshade = os.path.join(args.build, "rayshade", "rayshade")
    farm = os.path.join(args.build, "tools", "farm", "rayshade-farm")
    helper = os.path.join(args.build, "tools", "farm", "rayshade-farm-helper")
    cores = os.cpu_count() or 1
    w, h = args.resolution.split("x")
    scene = os.path.abspath(args.scene)
    work = tempfile.mkdtemp(prefix="farm-bench-")
    env = dict(os.environ)
    cluster = None
    try:
        if not args.no_slurm:
            if shutil.which("sbatch") is None:
                print("Slurm: sbatch not installed; Slurm figures left out")
            else:
                cluster = os.path.join(work, "slurm")
                subprocess.run([sys.executable, os.path.join(ROOT, "tests", "farm", "slurm_cluster.py"), "start", cluster],
                               check=True, stdout=subprocess.DEVNULL)
                env["SLURM_CONF"] = os.path.join(cluster, "slurm.conf")
        render = ["-q", "-R", w, h, scene]
        print(f"scene {os.path.basename(scene)} at {w}x{h}, {cores} cores")
        t1 = run([rayshade, "-t", "1", "-O", os.path.join(work, "one.png")] + render)
        print("  (wall time; CPU time of the processes started here, which does not count the Slurm tasks:\n"
              "   on a busy machine compare CPU times)")
        print(f"  one process, 1 thread:             {t1:7.2f} s   CPU {LAST_CPU:7.2f} s")
        tn = run([rayshade, "-O", os.path.join(work, "all.png")] + render)
        print(f"  one process, {cores} threads:            {tn:7.2f} s   CPU {LAST_CPU:7.2f} s")
        tl = run([sys.executable, farm, "submit", "--local", "--tiles", "2x2", "--"] + render[:-1] +
                 ["-O", os.path.join(work, "local.png"), scene], env={k: v for k, v in env.items() if k != "SLURM_CONF"})
        print(f"  4 local tasks (2x2 tiles, {cores} at once): {tl:7.2f} s   CPU {LAST_CPU:7.2f} s   identical: "
              f"{'yes' if same(os.path.join(work, 'local.png'), os.path.join(work, 'one.png')) else 'NO'}")
        if cluster:
            ts = run([sys.executable, farm, "submit", "--wait", "--tiles", "2x2", "--"] + render[:-1] +
                     ["-O", os.path.join(work, "slurm.png"), scene], env=env)
            print(f"  4 Slurm tasks (2x2 tiles, {cores} at once): {ts:7.2f} s   identical: "
                  f"{'yes' if same(os.path.join(work, 'slurm.png'), os.path.join(work, 'one.png')) else 'NO'}")

        print("farm overhead (16 tasks rendering 2x1 pixels each, 16x2 image, 8x2 tiles)")
        tiny = ["--tiles", "8x2", "--"]
        modes = [("local", ["--local"], {k: v for k, v in env.items() if k != "SLURM_CONF"})]
        if cluster:
            modes.append(("Slurm", ["--wait"], env))
        for name, flag, e in modes:
            out = os.path.join(work, f"tiny-{name}.png")
            start = time.time()
            wall = run([sys.executable, farm, "submit"] + flag + tiny + ["-q", "-R", "16", "2", "-O", out, scene], env=e)
            to_first = first_start(out + ".farm") - start
            print(f"  {name:5}: submit to first task start {to_first:5.2f} s; overhead per task "
                  f"{wall * cores / 16:5.2f} s (wall {wall:.2f} s for 16 tasks, {cores} at once)")

        print("merge of a 4096x4096 image from 16 tiles of 1024x1024, written as PNG")
        for name, ext, alpha in (("RGB mtv tiles", ".mtv", []), ("RGBA PNG tiles", ".png", ["-a"])):
            tile = os.path.join(work, "tile" + ext)
            subprocess.run([rayshade, "-q", "-p", "-R", "1024", "1024", "-O", tile] + alpha + [scene], check=True)
            words = []
            for j in range(4):
                for i in range(4):
                    words += [str(1024 * i), str(1024 * j), tile]
            best = min(run([helper, "merge", os.path.join(work, "merged.png"), "4096", "4096", str(cores)] + words)
                       for _ in range(3))
            print(f"  {name:15}: {best:5.2f} s (best of 3, {cores} threads)")
    finally:
        if cluster:
            subprocess.run([sys.executable, os.path.join(ROOT, "tests", "farm", "slurm_cluster.py"), "stop", cluster],
                           stdout=subprocess.DEVNULL)
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()

"""How closely rayshade's progress lines follow time during adaptive supersampling.

Renders each scene with standard error piped (so rayshade prints a line every 10%), notes
when each line arrives, and prints the fraction printed against the fraction of the render's
wall time elapsed at that moment, then the largest gap between what was shown and the time
(the line before a late one counts until it arrives). A progress report proportional to
time prints 10% at 10% of the time, and so on.
"""
import argparse
import os
import re
import subprocess
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def probe(rayshade, scene, args, out):
    start = time.monotonic()
    # In the scene's folder, where the original program found its data files.
    proc = subprocess.Popen([rayshade, *args, "-O", out, os.path.basename(scene)],
                            cwd=os.path.dirname(scene), stderr=subprocess.PIPE, text=True)
    marks = []
    for line in proc.stderr:
        m = re.search(r"(\d+)% done", line)
        if m:
            marks.append((int(m.group(1)), time.monotonic() - start))
    if proc.wait() != 0:
        raise SystemExit(f"rayshade failed on {scene}")
    total = time.monotonic() - start
    return [(percent, 100 * t / total) for percent, t in marks], total


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--shared", default=os.path.join(ROOT, "..", "shared"))
    parser.add_argument("--size", type=int, default=768)
    parser.add_argument("--samples", type=int, default=5)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("scenes", nargs="*", default=["balls", "glass", "planet"])
    a = parser.parse_args()
    rayshade = os.path.abspath(os.path.join(a.build, "rayshade", "rayshade"))
    out = os.path.abspath(os.path.join(a.build, "bench_progress.png"))
    args = ["-t", str(a.threads), "-S", str(a.samples), "-R", str(a.size), str(a.size)]
    print(f"rayshade {' '.join(args)}: printed% @ elapsed% of wall time")
    for name in a.scenes:
        scene = os.path.abspath(os.path.join(a.shared, "scenes", "rayshade", name + ".ray"))
        marks, total = probe(rayshade, scene, args, out)
        # Just before each line arrives, the previous one is still shown: a stall counts.
        shown = [0] + [p for p, _ in marks]
        gap = max(max(abs(p - t), abs(shown[i] - t)) for i, (p, t) in enumerate(marks))
        row = " ".join(f"{p}@{t:.0f}" for p, t in marks)
        print(f"{name:8s} {total:6.1f}s  {row}  (largest gap {gap:.0f} points)")
    os.remove(out)


if __name__ == "__main__":
    main()

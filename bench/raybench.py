"""Shared helpers of bench/accuracy.py and bench/paper_tables.py: running rayshade and
rayquery with timings, rewriting a scene's implicit blocks, eye rays from a scene's camera,
reading the statistics counters."""
import math
import os
import re
import subprocess
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)


def binaries(build):
    """Paths of rayshade and rayquery in a build folder (exits with a message if missing)."""
    paths = {name: os.path.join(build, name, name) for name in ("rayshade", "rayquery")}
    for name, path in paths.items():
        if not os.access(path, os.X_OK):
            raise SystemExit("build %s first (%s)" % (name, path))
    return paths


class Result:
    """A finished child: status, output, wall seconds, CPU seconds (user + system, all its
    threads) and peak RSS. The benches time with CPU seconds: the machines they run on are
    shared, and other jobs stretch wall time but not a single-threaded child's CPU time."""

    def __init__(self, status, stdout, stderr, seconds, cpu_seconds, max_rss_kib):
        self.status, self.stdout, self.stderr = status, stdout, stderr
        self.seconds, self.cpu_seconds, self.max_rss_kib = seconds, cpu_seconds, max_rss_kib


def run(command, stdin_text="", timeout=None):
    """Runs a command, feeding stdin_text, and measures it (Result). After `timeout` wall
    seconds the child is killed (status -9, `timed_out` set)."""
    with tempfile.TemporaryFile("w+") as inp, tempfile.TemporaryFile("w+") as out, \
            tempfile.TemporaryFile("w+") as err:
        inp.write(stdin_text)
        inp.seek(0)
        start = time.monotonic()
        proc = subprocess.Popen(command, stdin=inp, stdout=out, stderr=err, text=True)
        timer = threading.Timer(timeout, proc.kill) if timeout else None
        if timer:
            timer.start()
        _, status, usage = os.wait4(proc.pid, 0)
        seconds = time.monotonic() - start
        if timer:
            timer.cancel()
        proc.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        result = Result(proc.returncode, out.read(), err.read(), seconds,
                        usage.ru_utime + usage.ru_stime, usage.ru_maxrss)
        result.timed_out = bool(timeout) and seconds >= timeout
        return result


def rayquery(binary, scene_text, ray_lines, args=(), verbose=False, timeout=None):
    """rayquery on a scene given as text; -v adds the counters (stderr)."""
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "scene.ray")
        with open(path, "w") as fh:
            fh.write(scene_text)
        command = [binary] + list(args) + (["-v"] if verbose else []) + [path]
        return run(command, "".join(line + "\n" for line in ray_lines), timeout)


def accepts(binary, args):
    """Whether rayquery accepts these options (a method or knob it does not know is
    rejected with status 1 before any ray is read)."""
    scene = "surface s diffuse 1 1 1\nsphere s 1 0 0 0\n"
    return rayquery(binary, scene, [], args).status == 0


def parse_answers(stdout):
    """rayquery's lines as (hit, t, evals) tuples (t None for a miss)."""
    answers = []
    for line in stdout.splitlines():
        words = line.split()
        if not words:
            continue
        if words[0] == "hit":
            answers.append((True, float(words[1]), int(words[10])))
        else:
            answers.append((False, None, int(words[1])))
    return answers


def counters(text):
    """The statistics counters printed by -v ('name: value' lines)."""
    values = {}
    for line in text.splitlines():
        m = re.match(r"^(.*?):\s+([-0-9.eE+]+)\s*$", line.rstrip())
        if m:
            values[m.group(1).strip()] = float(m.group(2))
    return values


def implicit_totals(values, what):
    """Sum over implicit objects of the per-object counter `what`."""
    return sum(v for k, v in values.items()
               if k.startswith("Implicit object ") and k.endswith(": " + what))


def with_implicit_statements(scene, statements):
    """The scene with `statements` added as the last lines of every implicit block (so they
    override what the block declares: the last statement wins)."""
    out, inside = [], False
    for line in scene.splitlines():
        stripped = line.strip()
        if re.match(r"^(name\s+\S+\s+)?implicit\b", stripped):
            inside = True
        elif inside and stripped == "end":
            out += [" " + s for s in statements]
            inside = False
        out.append(line)
    return "\n".join(out) + "\n"


def camera(scene):
    """eyep, lookp, up, fov (horizontal, degrees) and screen size from a scene's text, each
    as a list of numbers (the first line starting with the keyword)."""
    counts = {"eyep": 3, "lookp": 3, "up": 3, "fov": 1, "screen": 2}
    found = {}
    for key, count in counts.items():
        m = re.search(r"^\s*%s\s+(.*)$" % key, scene, re.M)
        if m:
            found[key] = [float(x) for x in m.group(1).split()[:count]]
    return found


def normalize(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def eye_rays(eye, look, up, fov_degrees, width, height):
    """One ray through each pixel centre of a pinhole camera (horizontal field of view),
    as rayquery input lines with unit directions."""
    forward = normalize([b - a for a, b in zip(eye, look)])
    right = normalize(cross(forward, up))
    upv = cross(right, forward)
    half = math.tan(math.radians(fov_degrees) / 2)
    lines = []
    for j in range(height):
        y = (1 - 2 * (j + 0.5) / height) * half * height / width
        for i in range(width):
            x = (2 * (i + 0.5) / width - 1) * half
            d = normalize([f + x * r + y * u for f, r, u in zip(forward, right, upv)])
            lines.append("%r %r %r %r %r %r" % tuple(eye + d))
    return lines


def median(values):
    values = sorted(values)
    n = len(values)
    return values[n // 2] if n % 2 else 0.5 * (values[n // 2 - 1] + values[n // 2])


COMMENTARY = "<!-- commentary: kept when the tables are regenerated -->"


def write_with_commentary(path, generated):
    """Writes generated markdown to path, keeping the hand-written part of the existing
    file: everything from the COMMENTARY marker on."""
    kept = COMMENTARY + "\n"
    if os.path.exists(path):
        with open(path) as fh:
            old = fh.read()
        if COMMENTARY in old:
            kept = old[old.index(COMMENTARY):]
    with open(path, "w") as fh:
        fh.write(generated + "\n" + kept)

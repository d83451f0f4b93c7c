"""Runs the shell commands of the READMEs and doc pages, so that they work as written.

Convention (for everyone who writes documentation here):
  * A fenced block tagged ```sh holds commands a reader can paste into a shell at the
    repository root after the quick start (`scripts/quickstart.sh`) has built everything
    in build/. This test runs each such block with bash (-e -u -o pipefail) and requires
    exit status 0.
  * Commands that install packages, rebuild the tree, run the test suite or run for minutes
    go in blocks tagged ```sh skip (still highlighted as shell, never run here).
  * Output, usage synopses, syntax and scene text go in blocks tagged otherwise (```text,
    ```ray), or in indented blocks. An untagged or indented block whose first line starts
    like a command (a program of this project, cd, cmake, ctest, printf...) fails the
    test: it must be tagged, so that no command escapes the check by accident.
Each ```sh block runs in a fresh scratch directory that looks like the repository root:
symbolic links to the source tree's top-level entries (examples/, scripts/, docs/, ...),
build/ linking to the build tree, and ../shared to the shared folder; the build's
rayshade, rayquery and imgdiff are on PATH. Files a block writes land in the scratch
directory (or in build/), never in the source tree. Keep the commands cheap (small -R
sizes): the whole test should take seconds.

Usage: run_doc_commands.py --source DIR --build DIR --shared DIR --scratch DIR FILE.md...
"""
import argparse
import os
import re
import shutil
import subprocess
import sys

# First words that make a line a command (for the check on blocks of other kinds).
COMMAND_START = re.compile(
    r"^\s*(\$ )?\(?(rayshade|rayquery|imgdiff|build/|scripts/|bench/|tests/\S+\.sh|cd |cmake |ctest |"
    r"printf |echo |cat |python3 )")


def blocks(path):
    """(line number, info string or None for indented, lines) of each code block."""
    lines = open(path, encoding="utf-8").read().split("\n")
    out = []
    i, previous_blank = 0, True
    while i < len(lines):
        line = lines[i]
        fence = re.match(r"^(\s*)```(.*)$", line)
        if fence:
            indent, info = fence.group(1), fence.group(2).strip()
            j = i + 1
            while j < len(lines) and not lines[j].strip().startswith("```"):
                j += 1
            body = [l[len(indent):] if l.startswith(indent) else l for l in lines[i + 1:j]]
            out.append((i + 1, info, body))
            i, previous_blank = j + 1, False
            continue
        if line.startswith("    ") and previous_blank and not re.match(r"^\s*([-*|]|\d+\.)", line):
            j = i
            while j < len(lines) and (lines[j].startswith("    ") or not lines[j].strip()):
                j += 1
            out.append((i + 1, None, [l[4:] for l in lines[i:j]]))
            i, previous_blank = j, True
            continue
        previous_blank = not line.strip()
        i += 1
    return out


def scratch_root(args, name):
    """A fresh directory <scratch>/<name>/repo laid out like the repository root."""
    top = os.path.join(args.scratch, name)
    shutil.rmtree(top, ignore_errors=True)
    root = os.path.join(top, "repo")
    os.makedirs(root)
    for entry in os.listdir(args.source):
        if entry in (".git", "build") or entry.startswith("build"):
            continue
        os.symlink(os.path.join(args.source, entry), os.path.join(root, entry))
    os.symlink(args.build, os.path.join(root, "build"))
    os.symlink(args.shared, os.path.join(top, "shared"))
    return root


def main():
    parser = argparse.ArgumentParser()
    for option in ("--source", "--build", "--shared", "--scratch"):
        parser.add_argument(option, required=True)
    parser.add_argument("files", nargs="+")
    args = parser.parse_args()
    for option in ("source", "build", "shared", "scratch"):
        setattr(args, option, os.path.abspath(getattr(args, option)))
    env = dict(os.environ)
    tools = [os.path.join(args.build, d) for d in ("rayshade", "rayquery", os.path.join("tools", "imgdiff"))]
    env["PATH"] = os.pathsep.join(tools + [env.get("PATH", "")])
    failures, ran, skipped = [], 0, 0
    for doc in args.files:
        relative = os.path.relpath(doc, args.source)
        for number, info, body in blocks(doc):
            where = f"{relative}:{number}"
            if info == "sh":
                name = re.sub(r"[^A-Za-z0-9]+", "_", where)
                root = scratch_root(args, name)
                script = "set -euo pipefail\n" + "\n".join(body) + "\n"
                result = subprocess.run(["bash", "-c", script], cwd=root, env=env,
                                        capture_output=True, text=True, timeout=120)
                ran += 1
                if result.returncode != 0:
                    failures.append(f"{where}: exit status {result.returncode}\n"
                                    f"{script}--- stderr:\n{result.stderr[-2000:]}")
            elif info == "sh skip":
                skipped += 1
            elif not info:
                first = next((l for l in body if l.strip()), "")
                if COMMAND_START.match(first):
                    failures.append(f"{where}: a command outside a ```sh or ```sh skip block: {first.strip()}")
    print(f"{ran} command blocks run, {skipped} skipped (```sh skip)")
    for failure in failures:
        print("FAIL " + failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

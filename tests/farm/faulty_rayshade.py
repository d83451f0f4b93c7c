#!/usr/bin/env python3
"""A rayshade that fails once, for the farm's fault tests (given to rayshade-farm --rayshade).

Runs the real rayshade (FAULT_RAYSHADE) with the arguments given, except the first time its
arguments contain FAULT_MATCH (marked by creating FAULT_MARKER):
  FAULT_MODE=fail  exits with status 1 before rendering;
  FAULT_MODE=kill  starts the real render and stops it with SIGTERM as soon as it
                   traces (as Slurm does on preemption or at the time limit); rayshade
                   saves its partial state and the next attempt must continue from it (-c).
With FAULT_ALWAYS=1 every matching run fails (a task that never succeeds).
"""

import os
import signal
import subprocess
import sys

args = sys.argv[1:]
real = os.environ["FAULT_RAYSHADE"]
matches = os.environ.get("FAULT_MATCH", "\0") in " ".join(args)
marker = os.environ.get("FAULT_MARKER", "")
first = matches and (os.environ.get("FAULT_ALWAYS") == "1" or not os.path.exists(marker))
if not first:
    os.execv(real, [real] + args)
with open(marker, "w") as f:
    f.write("failed once\n")
if os.environ.get("FAULT_MODE") == "fail":
    print("faulty_rayshade: injected failure", file=sys.stderr)
    sys.exit(1)
output = args[len(args) - 1 - args[::-1].index("-O") + 1]
# Preempted as Slurm preempts (SIGTERM) once the render has started: rayshade saves its
# state at the next safe point and stops with a non-zero status.
child = subprocess.Popen([real] + args, stderr=subprocess.PIPE, text=True)
for line in child.stderr:
    sys.stderr.write(line)
    if line.startswith("Starting trace."):
        child.send_signal(signal.SIGTERM)
        break
for line in child.stderr:
    sys.stderr.write(line)
status = child.wait()
saved = os.path.exists(output + ".partial")
print(f"faulty_rayshade: stopped the render with SIGTERM (status {status}); partial state "
      f"{'saved' if saved else 'MISSING'}", file=sys.stderr)
sys.exit(status if status != 0 else 1)

#!/usr/bin/env python3
"""A real single-node Slurm cluster for the farm tests, everything under one directory.

    slurm_cluster.py start DIR   writes DIR/slurm.conf, starts munged, slurmctld and slurmd
                                 on loopback and waits until the node is idle
    slurm_cluster.py stop DIR    cancels the jobs, waits for the queue to empty, shuts the
                                 daemons down and ends munged, each by its process id

Ports are fixed (16817, 16818: not Slurm's defaults, so a system cluster is left alone);
the tests that use the cluster hold a CTest resource lock and run one at a time. The
commands find the configuration through SLURM_CONF=DIR/slurm.conf. A cluster that does not
come up is an error (status 1, with the daemons' logs), never a skipped test.
"""

import getpass
import os
import shutil
import signal
import subprocess
import sys
import time

CTLD_PORT, SLURMD_PORT = 16817, 16818


def fail(message, directory=None):
    sys.stderr.write(f"slurm_cluster: {message}\n")
    if directory:
        for log in ("munged.log", "slurmctld.log", "slurmd.log"):
            path = os.path.join(directory, log)
            if os.path.exists(path):
                with open(path, errors="replace") as f:
                    tail = f.read().splitlines()[-15:]
                sys.stderr.write(f"--- last lines of {path}:\n" + "\n".join(tail) + "\n")
    sys.exit(1)


def program(name):
    for d in ("", "/usr/sbin", "/usr/bin", "/sbin"):
        path = shutil.which(name) if not d else os.path.join(d, name)
        if path and os.access(path, os.X_OK):
            return path
    fail(f"'{name}' is not installed (scripts/install-deps.sh installs slurmctld slurmd "
         "slurm-client munge)")


def write_config(d):
    user = getpass.getuser()
    cpus = os.cpu_count() or 1
    conf = f"""# Written by tests/farm/slurm_cluster.py: one node on loopback, no cgroups, no database.
ClusterName=rayshadetest
SlurmctldHost=localhost
SlurmctldPort={CTLD_PORT}
SlurmdPort={SLURMD_PORT}
SlurmUser={user}
SlurmdUser={user}
AuthType=auth/munge
AuthInfo=socket={d}/munge.sock
CredType=cred/munge
StateSaveLocation={d}/state
SlurmdSpoolDir={d}/spool
SlurmctldPidFile={d}/slurmctld.pid
SlurmdPidFile={d}/slurmd.pid
SlurmctldLogFile={d}/slurmctld.log
SlurmdLogFile={d}/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
MailProg=/bin/true
MinJobAge=600
DependencyParameters=kill_invalid_depend
SchedulerParameters=sched_interval=1
NodeName=localhost NodeAddr=127.0.0.1 CPUs={cpus} RealMemory=1000 State=UNKNOWN
PartitionName=farmtest Nodes=localhost Default=YES MaxTime=INFINITE State=UP OverSubscribe=NO
"""
    with open(os.path.join(d, "slurm.conf"), "w") as f:
        f.write(conf)


def read_pid(path):
    try:
        with open(path) as f:
            return int(f.read().split()[0])
    except (OSError, ValueError, IndexError):
        return None


def alive(pid):
    try:
        os.kill(pid, 0)
        return True
    except OSError:
        return False


def node_state(env):
    r = subprocess.run(["sinfo", "-h", "-n", "localhost", "-o", "%T"], env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.DEVNULL, text=True)
    return r.stdout.strip()


def start(d):
    if os.path.exists(os.path.join(d, "pids")):
        stop(d, quiet=True)  # a cluster left by an aborted run
    for sub in ("state", "spool", "munge"):
        os.makedirs(os.path.join(d, sub), exist_ok=True)
    os.chmod(os.path.join(d, "munge"), 0o700)
    write_config(d)
    env = dict(os.environ, SLURM_CONF=os.path.join(d, "slurm.conf"))
    key = os.path.join(d, "munge", "munge.key")
    if not os.path.exists(key):
        if subprocess.run([program("mungekey"), "-c", "-k", key]).returncode != 0:
            fail("mungekey could not create a key", d)
    munged = [program("munged"), f"--socket={d}/munge.sock", f"--key-file={key}",
              f"--pid-file={d}/munged.pid", f"--log-file={d}/munged.log", f"--seed-file={d}/munge/seed",
              "--force"]
    if subprocess.run(munged).returncode != 0:
        fail("munged did not start", d)
    pids = {"munged": read_pid(f"{d}/munged.pid")}
    if subprocess.run([program("slurmctld"), "-f", env["SLURM_CONF"]], env=env).returncode != 0:
        fail("slurmctld did not start", d)
    if subprocess.run([program("slurmd"), "-f", env["SLURM_CONF"], "-N", "localhost"], env=env).returncode != 0:
        fail("slurmd did not start", d)
    deadline = time.time() + 30
    while time.time() < deadline:
        pids["slurmctld"] = pids.get("slurmctld") or read_pid(f"{d}/slurmctld.pid")
        pids["slurmd"] = pids.get("slurmd") or read_pid(f"{d}/slurmd.pid")
        if node_state(env) == "idle" and pids["slurmctld"] and pids["slurmd"]:
            with open(os.path.join(d, "pids"), "w") as f:
                f.write(" ".join(f"{k}={v}" for k, v in pids.items() if v) + "\n")
            print(f"slurm cluster up in {d} ({pids})")
            return
        time.sleep(0.2)
    with open(os.path.join(d, "pids"), "w") as f:
        f.write(" ".join(f"{k}={v}" for k, v in pids.items() if v) + "\n")
    fail(f"the node did not become idle within 30 s (state '{node_state(env)}')", d)


def stop(d, quiet=False):
    env = dict(os.environ, SLURM_CONF=os.path.join(d, "slurm.conf"))
    pids = {}
    try:
        with open(os.path.join(d, "pids")) as f:
            for word in f.read().split():
                name, _, pid = word.partition("=")
                pids[name] = int(pid)
    except OSError:
        if not quiet:
            fail(f"no cluster was started in {d} (no pids file)")
        return
    subprocess.run(["scancel", "-p", "farmtest"], env=env, stderr=subprocess.DEVNULL)
    deadline = time.time() + 20
    while time.time() < deadline:
        r = subprocess.run(["squeue", "-h"], env=env, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        if r.returncode != 0 or not r.stdout.strip():
            break
        time.sleep(0.3)
    subprocess.run(["scontrol", "shutdown"], env=env, stderr=subprocess.DEVNULL)
    for name in ("slurmd", "slurmctld", "munged"):
        pid = pids.get(name)
        if not pid:
            continue
        if name == "munged" and alive(pid):
            os.kill(pid, signal.SIGTERM)
        for _ in range(100):
            if not alive(pid):
                break
            time.sleep(0.1)
        if alive(pid):
            os.kill(pid, signal.SIGKILL)
    os.remove(os.path.join(d, "pids"))
    if not quiet:
        print(f"slurm cluster in {d} stopped")


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in ("start", "stop"):
        fail("usage: slurm_cluster.py start|stop DIR")
    directory = os.path.abspath(sys.argv[2])
    os.makedirs(directory, exist_ok=True)
    (start if sys.argv[1] == "start" else stop)(directory)

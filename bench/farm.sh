#!/usr/bin/env bash
# Render-farm figures (issue 16): one process against 4 local and 4 Slurm tasks on a scene
# of ~30 s on one core, the farm's overhead per task, and the merge time of a 4096x4096
# image from 16 tiles (see bench/farm.py). The Slurm figures start a single-node test
# cluster (tests/farm/slurm_cluster.py; needs the slurmctld slurmd slurm-client munge
# packages, scripts/install-deps.sh) and stop it at the end.
# Usage: bench/farm.sh [--build DIR] [--scene FILE] [--resolution WxH] [--no-slurm]
set -euo pipefail
exec python3 "$(cd "$(dirname "$0")" && pwd)/farm.py" "$@"

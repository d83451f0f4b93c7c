#!/usr/bin/env bash
# Embree 3 against our own ray tracing on the SPD scenes (issue 15): build and trace CPU
# seconds, rays per second and the precision of its single-precision hits; see bench/embree.py.
# Needs a build configured with -DRAYSHADE_EMBREE_EVAL=ON (apt-get install -y libembree-dev).
# Usage: bench/embree.sh [--build DIR] [--kit DIR] [--rounds N] [scene ...]
set -euo pipefail
exec python3 "$(cd "$(dirname "$0")" && pwd)/embree.py" "$@"

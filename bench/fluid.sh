#!/usr/bin/env bash
# Implicit fluids: random-walk chains of 100 to 1,000,000 Gascuel points, build and search
# cost, memory and agreement with the exact method; see bench/fluid.py.
# Usage: bench/fluid.sh [--build DIR] [--sizes 100,10000,100000,1000000] [--threads 2]
#        [--rays 200] [--no-check] [--blob] [--no-povray] [--keep DIR]
set -euo pipefail
exec python3 "$(cd "$(dirname "$0")" && pwd)/fluid.py" "$@"

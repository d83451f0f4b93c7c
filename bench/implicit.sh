#!/usr/bin/env bash
# Implicit-surface benchmark (N point skeletons along a random-walk chain, patches and kb89
# against POV-Ray's blob); see bench/implicit.py for what is measured and printed.
# Usage: bench/implicit.sh [--build DIR] [--sizes 10,100,1000,10000,100000] [--kb89-max N]
#        [--no-povray] [--keep DIR] [--tolerance auto|EPS]
set -euo pipefail
exec python3 "$(cd "$(dirname "$0")" && pwd)/implicit.py" "$@"

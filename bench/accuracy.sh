#!/usr/bin/env bash
# Speed against accuracy of the implicit intersection methods: writes
# docs/images/speed-accuracy.png, docs/images/cost-vs-skeletons.png and docs/speed-accuracy.md
# (see bench/accuracy.py). Needs matplotlib (Debian: apt-get install python3-matplotlib); the
# first python3 on PATH that imports it is used, else /usr/bin/python3.
# Usage: bench/accuracy.sh [--build DIR] [--rays N] [--sizes 10,100,1000,10000] [--docs DIR]
set -euo pipefail
python=python3
if ! python3 -c 'import matplotlib' 2>/dev/null; then
    python=/usr/bin/python3
fi
exec "$python" "$(cd "$(dirname "$0")" && pwd)/accuracy.py" "$@"

#!/usr/bin/env bash
# Cost of skeleton motion blur (issue 14): a 1,000-point chain moving by about its own
# thickness during the shutter against the same chain static; see bench/motion.py.
# Usage: bench/motion.sh [--build DIR] [--size 256] [--samples 3] [--repeat 3] [--callgrind]
set -euo pipefail
exec python3 "$(cd "$(dirname "$0")" && pwd)/motion.py" "$@"

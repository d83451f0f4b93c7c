#!/usr/bin/env bash
# How closely the progress lines follow time during adaptive supersampling; see
# bench/progress.py for what is measured and printed.
# Usage: bench/progress.sh [--build DIR] [--size 768] [--samples 5] [--threads 2] [scene ...]
set -euo pipefail
exec python3 "$(cd "$(dirname "$0")" && pwd)/progress.py" "$@"

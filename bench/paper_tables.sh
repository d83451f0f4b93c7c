#!/usr/bin/env bash
# The paper's tables (Gascuel 1995 §3.2-3.3) on our test set; see bench/paper_tables.py.
# Usage: bench/paper_tables.sh [--build DIR] [--reps N] [--depths 0,1,...,10] [--out FILE]
set -euo pipefail
exec python3 "$(cd "$(dirname "$0")" && pwd)/paper_tables.py" "$@"

#!/usr/bin/env bash
# Cost of deformed implicit patches against undeformed ones on the figure-7 scene (issue 5);
# see bench/contact.py for what is measured and printed.
# Usage: bench/contact.sh [--build DIR] [--size 512] [--repeat 5] [--threads 1]
set -euo pipefail
exec python3 "$(cd "$(dirname "$0")" && pwd)/contact.py" "$@"

#!/usr/bin/env bash
# The one build of the README's commands: every program and test in build/, Release, warnings
# as errors. scripts/quickstart.sh and scripts/run-tests.sh both run it, so whichever comes
# second finds nothing to rebuild.
# Usage: scripts/build.sh [extra cmake configure arguments]
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRAYSHADE_WERROR=ON "$@"
cmake --build build -j"$(nproc 2>/dev/null || echo 2)"

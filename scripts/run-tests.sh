#!/usr/bin/env bash
# Builds everything from scratch in build/ (Release, warnings as errors) and runs every test:
# unit tests and the image regression tests against ../shared/reference.
# Usage: scripts/run-tests.sh [extra ctest arguments]
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRAYSHADE_WERROR=ON
cmake --build build -j"$jobs"
ctest --test-dir build -j"$jobs" --output-on-failure "$@"

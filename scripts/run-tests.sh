#!/usr/bin/env bash
# Builds everything in build/ (scripts/build.sh: Release, warnings as errors; nothing to do
# after scripts/quickstart.sh) and runs every test: unit tests and the image regression
# tests against ../shared/reference.
# Usage: scripts/run-tests.sh [extra ctest arguments]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
ctest --test-dir build -j"$(nproc 2>/dev/null || echo 2)" --output-on-failure "$@"

#!/usr/bin/env bash
# Builds the tree with AddressSanitizer and UndefinedBehaviorSanitizer (RAYSHADE_SANITIZE=ON)
# in build-asan/ and runs the unit tests, the malformed-input corpus, the numerical-hygiene
# scenes and a fast subset of the render regression tests (256x256 balls, csg, blob, planet)
# under them. Any sanitizer report aborts the test that triggered it.
# Usage: scripts/run-sanitizer-tests.sh [extra ctest arguments]
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=2
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# -O1 without debug information: the usual optimisation for sanitizer runs, and it keeps
# this second full build (CI runs it after the Release one) to a few minutes.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1" -DRAYSHADE_WERROR=ON \
      -DRAYSHADE_SANITIZE=ON
cmake --build build-asan -j"$jobs"
ctest --test-dir build-asan -j"$jobs" --output-on-failure -L unit "$@"
ctest --test-dir build-asan -j"$jobs" --output-on-failure \
      -R '^(bad_input|numerics|fuzz_regression)\.|^(balls|csg|blob|planet)_256$' "$@"

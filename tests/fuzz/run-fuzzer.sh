#!/usr/bin/env bash
# Builds the libFuzzer front-end target with clang (build-fuzz/) and fuzzes it.
#     tests/fuzz/run-fuzzer.sh [seconds] [extra libFuzzer options]
# The seed corpus is every scene we ship (../shared/scenes/rayshade and examples/), both raw
# and through `cpp -P`; new inputs accumulate in build-fuzz/corpus, crashers in
# build-fuzz/artifacts. The log is build-fuzz/fuzz.log. Default: 1800 seconds. Standard input
# is empty, since an input may include /dev/stdin.
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-1800}
shift || true
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DRAYSHADE_FUZZ=ON -DRAYSHADE_BUILD_TESTS=OFF
cmake --build build-fuzz -j2 --target fuzz_frontend
seeds=build-fuzz/seeds
mkdir -p "$seeds" build-fuzz/corpus build-fuzz/artifacts
shared=$(cmake -L -N build-fuzz | sed -n 's/^RAYSHADE_SHARED_DIR:PATH=//p')
for scene in "$shared"/scenes/rayshade/*.ray examples/*.ray; do
    [ -e "$scene" ] || continue
    base=$(basename "$scene" .ray)
    cp "$scene" "$seeds/$base.raw.ray"
    cpp -P -I"$(dirname "$scene")" "$scene" >"$seeds/$base.cpp.ray" 2>/dev/null || rm -f "$seeds/$base.cpp.ray"
done
ASAN_OPTIONS=detect_leaks=1 build-fuzz/tests/fuzz/fuzz_frontend build-fuzz/corpus "$seeds" \
    -dict=tests/fuzz/rayshade.dict -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
    -max_total_time="$seconds" -print_final_stats=1 -artifact_prefix=build-fuzz/artifacts/ \
    "$@" </dev/null 2>&1 | tee build-fuzz/fuzz.log

#!/usr/bin/env bash
# Renders one numerical-hygiene scene small and checks the outcome:
#     run_numerics.sh <rayshade> <imgdiff> <scene> <workdir>
# The render must exit 0 and write an image that decodes (imgdiff compares it with itself),
# and its statistics (-v) must not contain the counters "Non-finite pixel values" (a NaN or
# infinite colour reached a pixel) or "Non-finite or zero normals replaced" (a primitive
# returned a NaN, infinite or zero normal, which the tracer's guard had to replace). Both
# counters are printed only when non-zero.
set -u
rayshade=$1 imgdiff=$2 scene=$3 workdir=$4
name=$(basename "$scene" .ray)
mkdir -p "$workdir"
out="$workdir/$name.png"
stats="$workdir/$name.stats"
rm -f "$out"
timeout 120 "$rayshade" -q -v -R 64 64 -V "$stats" -O "$out" "$scene"
rc=$?
if [ "$rc" -ne 0 ]; then
    echo "rayshade exited with status $rc"
    exit 1
fi
if ! "$imgdiff" "$out" "$out" >/dev/null; then
    echo "the output image $out does not decode"
    exit 1
fi
if grep -E "Non-finite" "$stats"; then
    echo "non-finite values reached the shading or the image (see $stats)"
    exit 1
fi
exit 0

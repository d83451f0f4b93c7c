#!/usr/bin/env bash
# Renders patches_vs_sum.ray with method patches and with kb89 (the plain sum) and checks
# that the pictures agree pixel for pixel up to a tiny fraction of pixels, which may differ
# where a ray grazes the surface within the root tolerance.
# Usage: compare_methods.sh RAYSHADE IMGDIFF SCENE WORKDIR
set -euo pipefail
rayshade=$1 imgdiff=$2 scene=$3 work=$4
mkdir -p "$work"
"$rayshade" -q -P "-DMETHOD=patches" -O "$work/patches.png" "$scene"
"$rayshade" -q -P "-DMETHOD=kb89" -O "$work/sum.png" "$scene"
"$imgdiff" --pixels 2 0.002 --mean 0.001 --max 0.02 --frac 0.002 --bright 0.001 \
    --diff "$work/difference.png" "$work/patches.png" "$work/sum.png"

#!/usr/bin/env bash
# Renders SCENE with its own implicit method and again with rayshade's implicit overrides
# (the remaining arguments, e.g. -M exact) and checks that the pictures agree up to a tiny
# fraction of pixels (rays grazing the surface within the root tolerance may differ).
# Usage: compare_override.sh RAYSHADE IMGDIFF SCENE WORKDIR OVERRIDE...
set -euo pipefail
rayshade=$1 imgdiff=$2 scene=$3 work=$4
shift 4
mkdir -p "$work"
"$rayshade" -q -O "$work/declared.png" "$scene"
"$rayshade" -q "$@" -O "$work/override.png" "$scene"
"$imgdiff" --pixels 2 0.002 --mean 0.001 --max 0.02 --frac 0.002 --bright 0.001 \
    --diff "$work/difference.png" "$work/declared.png" "$work/override.png"

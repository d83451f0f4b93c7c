#!/usr/bin/env bash
# Renders a scene with 1, 2, 3 and 5 threads and checks the PNG files are byte-identical:
# every sample's random stream is keyed by its pixel and cell, never by thread.
# Usage: same_image_any_threads.sh RAYSHADE SCENE WORKDIR [rayshade options...]
set -euo pipefail
rayshade=$1 scene=$2 work=$3
shift 3
mkdir -p "$work"
cd "$(dirname "$scene")"
for t in 1 2 3 5; do
  "$rayshade" -q -t "$t" "$@" -O "$work/t$t.png" "$(basename "$scene")"
done
for t in 2 3 5; do
  cmp "$work/t1.png" "$work/t$t.png" || { echo "image with $t threads differs from 1 thread"; exit 1; }
done
echo "identical images with 1, 2, 3 and 5 threads"

#!/usr/bin/env bash
# Skeleton motion blur against an animated translate (issue 14, check a): the same blob,
# moved by its skeleton's coordinates or by the object's transform, with the shutter open
# and the same samples, must pass imgdiff at the regression thresholds; the control, the
# skeleton scene with the shutter closed (sharp), must fail them, so the check can fail.
# Usage: motion_translate.sh RAYSHADE IMGDIFF SCENE WORKDIR
set -euo pipefail
rayshade=$1 imgdiff=$2 scene=$3 work=$4
mkdir -p "$work"
"$rayshade" -q -O "$work/skeleton.png" "$scene"
"$rayshade" -q -P -DTRANSLATE -O "$work/translate.png" "$scene"
"$rayshade" -q -P -DSHARP -O "$work/sharp.png" "$scene"
"$imgdiff" "$work/skeleton.png" "$work/translate.png"
if "$imgdiff" "$work/sharp.png" "$work/translate.png" > "$work/control.txt"; then
    echo "control: the sharp render passes against the blurred one" >&2
    exit 1
fi
echo "skeleton motion blur matches the animated translate; the sharp control fails"

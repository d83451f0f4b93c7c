#!/usr/bin/env bash
# contact auto against declared contacts (contact_auto.ray): frame 0, where the parts are
# apart, must equal the scene without contacts, and frame 1, where they interpenetrate, the
# scene with the pair declared, byte for byte; frame 1 must differ from the scene without
# contacts (so the comparison can fail), and -v must report the one automatic contact.
# Usage: contact_auto.sh RAYSHADE SCENE WORKDIR
set -euo pipefail
rayshade=$1 scene=$2 work=$3
mkdir -p "$work"
"$rayshade" -q -O "$work/auto.png" "$scene"
"$rayshade" -q -A 0 -N 1 -P -DNONE -O "$work/none0.png" "$scene"
"$rayshade" -q -A 1 -N 1 -P -DNONE -O "$work/none1.png" "$scene"
"$rayshade" -q -A 1 -N 1 -P -DDECLARED -O "$work/declared1.png" "$scene"
cmp "$work/auto_f000.png" "$work/none0.png"
cmp "$work/auto_f001.png" "$work/declared1.png"
if cmp -s "$work/auto_f001.png" "$work/none1.png"; then
    echo "frame 1 with contact auto equals the scene without contacts" >&2
    exit 1
fi
"$rayshade" -v -q -A 1 -N 1 -O "$work/verbose.png" "$scene" 2> "$work/verbose.txt"
grep -q "automatic contacts:[[:space:]]*1$" "$work/verbose.txt" || {
    echo "-v does not report one automatic contact:" >&2
    grep -i contact "$work/verbose.txt" >&2 || true
    exit 1
}
echo "contact auto: frame 0 = no contacts, frame 1 = declared pair"

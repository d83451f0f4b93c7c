#!/usr/bin/env bash
# Feeds one malformed scene to the real renderer and checks the rejection:
#     run_bad_input.sh <rayshade> <scene> <expected-stderr-file> <expected-status> <workdir> [option ...]
# runs `rayshade -q [option ...] -O <workdir>/<name>.png <scene>` (-q: no progress or timing lines) in the
# scene's directory (so messages name the scene by its bare file name), then requires the exit
# status to be <expected-status>, standard error to equal the expected file byte for byte, and
# no image to have been written.
set -u
rayshade=$1 scene=$2 expected=$3 status=$4 workdir=$5
shift 5
name=$(basename "$scene" .ray)
mkdir -p "$workdir"
out="$workdir/$name.png"
err="$workdir/$name.stderr"
rm -f "$out" "$out.partial"
cd "$(dirname "$scene")" || exit 1
timeout 60 "$rayshade" -q "$@" -O "$out" "$(basename "$scene")" >/dev/null 2>"$err"
got=$?
fail=0
if [ "$got" -ne "$status" ]; then
    echo "exit status $got, expected $status"
    fail=1
fi
if ! cmp -s "$err" "$expected"; then
    echo "standard error differs from $expected:"
    diff "$expected" "$err" | head -20
    fail=1
fi
if [ -e "$out" ]; then
    echo "an image was written although the scene is invalid: $out"
    fail=1
fi
exit $fail

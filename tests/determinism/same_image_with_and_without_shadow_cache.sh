#!/usr/bin/env bash
# Renders a scene with the shadow cache (the default) on one and on three threads, and
# without it (-s), and checks the PNG files are byte-identical: a cached blocker is only a
# hint tested with the world's own query, so it may change statistics and time, never a
# pixel. HITS says what the statistics must show: `some` shadow rays answered by the cache,
# or `none` (a scene whose blockers are CSG or transformed aggregates, which are not cached).
# Usage: same_image_with_and_without_shadow_cache.sh RAYSHADE SCENE WORKDIR HITS [rayshade options...]
set -euo pipefail
rayshade=$1 scene=$2 work=$3 expect=$4
shift 4
mkdir -p "$work"
cd "$(dirname "$scene")"
name=$(basename "$scene")
"$rayshade" -t 1 "$@" -V "$work/cached.txt" -O "$work/cached.png" "$name"
"$rayshade" -q -t 3 "$@" -O "$work/cached3.png" "$name"
"$rayshade" -s -t 1 "$@" -V "$work/uncached.txt" -O "$work/uncached.png" "$name"
cmp "$work/cached.png" "$work/uncached.png" || { echo "the shadow cache changed the image"; exit 1; }
cmp "$work/cached.png" "$work/cached3.png" || { echo "the shadow cache made the image depend on threads"; exit 1; }
hits=$(sed -n 's/^Shadow cache hits:[[:space:]]*\([0-9]*\).*/\1/p' "$work/cached.txt")
[ -n "$hits" ] || { echo "no shadow cache statistics"; exit 1; }
case $expect in
  some) [ "$hits" -gt 0 ] || { echo "the shadow cache answered no shadow ray"; exit 1; } ;;
  none) [ "$hits" -eq 0 ] || { echo "the shadow cache answered $hits rays of uncached blockers"; exit 1; } ;;
  *) echo "HITS must be some or none" >&2; exit 2 ;;
esac
! grep -q '^Shadow cache hits' "$work/uncached.txt" || { echo "-s left the shadow cache on"; exit 1; }
grep -q '^Shadow cache disabled' "$work/uncached.txt" || { echo "-s not reported"; exit 1; }
echo "identical images with and without the shadow cache ($hits cache hits)"

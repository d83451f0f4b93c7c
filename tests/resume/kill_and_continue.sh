#!/usr/bin/env bash
# Kills renders at random moments (SIGKILL and SIGINT) and checks that nothing is lost:
# the output name never holds a truncated image, and continuing with -c from the partial
# state yields exactly the image of an uninterrupted render.
# Usage: kill_and_continue.sh RAYSHADE SCENE WORKDIR
set -euo pipefail
rayshade=$1 scene=$2 work=$3
mkdir -p "$work"
cd "$work"
rm -f ref.png out.png out.png.partial out.png.tmp-* out.png.partial.tmp-*
args=(-q -R 320 240 -S 4)
"$rayshade" "${args[@]}" -O ref.png "$scene"
export RAYSHADE_CHECKPOINT_SECONDS=0.05

seed=${RANDOM_SEED:-$$}
RANDOM=$seed
echo "seed $seed"
for round in 1 2 3 4 5 6; do
  rm -f out.png out.png.partial
  signal=KILL
  [ $((round % 2)) -eq 0 ] && signal=INT
  delay=$(awk -v r=$RANDOM 'BEGIN { printf "%.2f", 0.05 + (r % 100) / 100.0 * 0.6 }')
  "$rayshade" "${args[@]}" -t 2 -O out.png "$scene" 2> /dev/null &
  pid=$!
  sleep "$delay"
  kill -s "$signal" "$pid" 2> /dev/null || true
  wait "$pid" 2> /dev/null || true
  # out.png is complete if present. A SIGKILL that lands while a file is being written
  # leaves that write's temporary file (nothing can remove it); after SIGINT none may remain.
  if ls out.png.tmp-* out.png.partial.tmp-* > /dev/null 2>&1; then
    if [ "$signal" = INT ]; then echo "round $round: stray temporary file after SIGINT"; exit 1; fi
    rm -f out.png.tmp-* out.png.partial.tmp-*
  fi
  if [ -f out.png ] && ! cmp -s out.png ref.png; then
    echo "round $round ($signal after ${delay}s): out.png exists but differs from the reference"
    exit 1
  fi
  if [ ! -f out.png ]; then
    if [ ! -f out.png.partial ]; then
      echo "round $round ($signal after ${delay}s): killed before the first checkpoint; rendering afresh"
      "$rayshade" "${args[@]}" -O out.png "$scene"
    else
      "$rayshade" "${args[@]}" -t 1 -c -O out.png "$scene"
    fi
  fi
  cmp out.png ref.png || { echo "round $round ($signal after ${delay}s): continued image differs"; exit 1; }
  [ ! -f out.png.partial ] || { echo "round $round: partial state left behind"; exit 1; }
  echo "round $round ($signal after ${delay}s): ok"
done

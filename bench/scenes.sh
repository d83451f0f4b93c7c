#!/usr/bin/env bash
# Renders the original program's example scenes at 1024x1024 with one thread and with all
# threads, and prints seconds, rays per second and the speed-up over the original program
# (its single-threaded CPU seconds on this machine class, from the project's issue #2).
#
# Usage: bench/scenes.sh [build-dir] [scene ...]     (default: build, all nine scenes)
# Figures come from one run each; the machines are shared, so compare ratios measured in
# the same run rather than absolute seconds across runs.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "${1:-$here/build}" && pwd)"
shift || true
rayshade="$build/rayshade/rayshade"
scenes_dir="${RAYSHADE_SHARED_DIR:-$here/../shared}/scenes/rayshade"
[ -x "$rayshade" ] || { echo "build rayshade first (scripts/run-tests.sh)" >&2; exit 1; }
[ -d "$scenes_dir" ] || { echo "no scenes at $scenes_dir" >&2; exit 1; }
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(ashtray balls blob boxball coin csg glass mtv planet)
threads=$(nproc)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

declare -A original=([ashtray]=0.96 [balls]=0.65 [blob]=0.88 [boxball]=0.46 [csg]=1.1
                     [glass]=8.3 [mtv]=11.2 [planet]=0.35 [coin]=)

# Runs one render; prints "<cpu seconds> <wall seconds> <total rays>".
run() {
  local scene=$1 t=$2 extra=()
  [ "$scene" = ashtray ] && extra=(-P "-DIMAGEFILE=testtex.img")
  [ "$scene" = coin ] && extra=(-N 1)
  (cd "$scenes_dir" &&
   /usr/bin/time -f "%U %S %e" -o "$tmp/time" "$rayshade" -q -t "$t" -R 1024 1024 \
       "${extra[@]}" -V "$tmp/stats" -O "$tmp/out.png" "$scene.ray" > /dev/null)
  local rays
  rays=$(awk -F'\t+' '/^Total rays:/ {print $2}' "$tmp/stats")
  awk -v rays="$rays" '{printf "%.2f %.2f %s\n", $1 + $2, $3, rays}' "$tmp/time"
}

printf "%-8s %9s | %9s %9s %12s %8s | %9s %8s\n" scene "orig cpu" "1T cpu" "1T wall" "rays/s (1T)" "vs orig" \
       "${threads}T wall" "scaling"
for scene in "${scenes[@]}"; do
  read -r cpu1 wall1 rays < <(run "$scene" 1)
  read -r _ wallN _ < <(run "$scene" "$threads")
  orig=${original[$scene]:-}
  awk -v s="$scene" -v o="$orig" -v c="$cpu1" -v w="$wall1" -v r="$rays" -v wn="$wallN" 'BEGIN {
    vs = (o == "" ? "-" : sprintf("%.2fx", o / c));
    printf "%-8s %9s | %9.2f %9.2f %12.0f %8s | %9.2f %7.2fx\n", s, (o == "" ? "-" : o), c, w, r / w, vs, wn, w / wn }'
done

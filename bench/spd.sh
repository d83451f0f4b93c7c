#!/usr/bin/env bash
# Renders Haines' Standard Procedural Databases (the shared bench kit's spd/ folder) with our
# program, the original Rayshade 4.0 and, when installed, POV-Ray 3.7, interleaved in one run,
# single-threaded at the files' 512x512 with one ray per pixel, and prints CPU seconds, the
# ratios, primitive tests and rays per second, and how close our pixels are to the original's.
#
# Usage: bench/spd.sh [-b build-dir] [-c base-build-dir] [-r rounds] [-m modes] [scene ...]
#   scenes: balls gears mount teapot tetra tree (default: all)
#   -c: also run that build's rayshade (e.g. the main branch's), interleaved with ours on
#       every file, and print its CPU seconds, setup and our ratio to it ("vs base")
#   modes (comma-separated, default grid,list,default):
#     grid     NAME.grid.ray (objects in one hand-sized grid): ours, the original, POV-Ray
#     list     NAME.ray (everything in the top-level list): ours only (the original does
#              not accelerate the top-level list and takes minutes)
#     default  NAME.grid.ray without its `sample 1 nojitter` (Rayshade's default adaptive
#              jittered sampling): ours and the original
#     threads  NAME.grid.ray at -t 1 and -t 2: wall seconds and the speedup (ours, and the
#              base build with -c), of the whole render and of its setup (-R 1 1); wall
#              time, so only meaningful on an otherwise idle machine (the load is printed)
#   rounds: every figure is the minimum over this many interleaved rounds (default 1)
#
# Our CPU time is the whole process's (user + system, from /usr/bin/time). Its parse/setup
# part is the CPU time of the same command at -R 1 1 (reading the file, building the grids
# and hierarchies, rendering one pixel); render = whole - parse/setup. The original's figure
# is its whole process; POV-Ray's are its own parse+bounding and trace CPU seconds, and
# "pov whole" its whole process. "fid" is the mean absolute difference between our image and
# the original's after a 4x4 box filter (tools/imgdiff; SPD README: below 0.001 is a match,
# except where the original's own grid defect shows).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="$here/build"
rounds=1
modes="grid,list,default"
base=""
while getopts "b:c:r:m:" opt; do
  case $opt in
    b) build="$(cd "$OPTARG" && pwd)" ;;
    r) rounds=$OPTARG ;;
    m) modes=$OPTARG ;;
    c) base="$(cd "$OPTARG" && pwd)" ;;
    *) sed -n '2,28p' "$0" >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
shared="${RAYSHADE_SHARED_DIR:-$here/../shared}"
spd="$shared/bench/spd/scenes"
original="$shared/reference/bin/rayshade-original"
rayshade="$build/rayshade/rayshade"
imgdiff="$build/tools/imgdiff/imgdiff"
baseRayshade=""
[ -n "$base" ] && baseRayshade="$base/rayshade/rayshade"
for f in "$rayshade" "$imgdiff" $baseRayshade; do
  [ -x "$f" ] || { echo "missing $f: build the rayshade and imgdiff targets first" >&2; exit 1; }
done
[ -d "$spd" ] || { echo "no SPD scenes at $spd" >&2; exit 1; }
have_original=0; [ -x "$original" ] && have_original=1
have_pov=0; command -v povray > /dev/null && have_pov=1
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(balls gears mount teapot tetra tree)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Decompress what the chosen modes need, once.
for s in "${scenes[@]}"; do
  [ -f "$spd/$s.grid.ray.gz" ] || { echo "unknown scene $s" >&2; exit 2; }
  zcat "$spd/$s.grid.ray.gz" > "$tmp/$s.grid.ray"  # also what threads mode renders
  [[ ,$modes, == *,list,* ]] && zcat "$spd/$s.ray.gz" > "$tmp/$s.list.ray"
  [[ ,$modes, == *,default,* ]] && grep -v '^sample 1 nojitter' "$tmp/$s.grid.ray" > "$tmp/$s.default.ray"
  [[ ,$modes, == *,grid,* && $have_pov == 1 ]] && zcat "$spd/$s.pov.gz" > "$tmp/$s.pov"
done

# min KEY VALUE: keeps the smallest VALUE seen for KEY in $tmp/min.
declare -A best
keep_min() {
  local k=$1 v=$2
  if [ -z "${best[$k]:-}" ] || awk -v a="$v" -v b="${best[$k]}" 'BEGIN { exit !(a < b) }'; then
    best[$k]=$v
  fi
}
cpu_of() { awk '{ printf "%.3f", $1 + $2 }' "$1"; }

# ours FILE TAG [BINARY]: whole-process and setup CPU, primitive tests, total rays; keeps
# the image. BINARY defaults to our rayshade.
ours() {
  local file=$1 tag=$2 binary=${3:-$rayshade}
  (cd "$tmp" && /usr/bin/time -f "%U %S" -o "$tmp/time" "$binary" -q -t 1 -V "$tmp/stats" \
      -O "$tmp/$tag.ours.png" "$file" > /dev/null)
  keep_min "$tag.cpu" "$(cpu_of "$tmp/time")"
  best[$tag.tests]=$(awk -F'\t+' '/^Total prim. intersection tests:/ { split($2, a, " "); print a[1] }' "$tmp/stats")
  best[$tag.rays]=$(awk -F'\t+' '/^Total rays:/ { print $2 }' "$tmp/stats")
  (cd "$tmp" && /usr/bin/time -f "%U %S" -o "$tmp/time" "$binary" -q -t 1 -R 1 1 \
      -O "$tmp/setup.png" "$file" > /dev/null)
  keep_min "$tag.setup" "$(cpu_of "$tmp/time")"
}
# ours_and_base FILE TAG: ours, then the base build's (as TAG.base) when -c gave one.
ours_and_base() {
  ours "$1" "$2"
  [ -n "$baseRayshade" ] && ours "$1" "$2.base" "$baseRayshade"
  return 0
}
# wall BINARY THREADS FILE KEY [ARGS...]: the wall seconds of one render, to the
# millisecond (the large scenes' setups take a tenth of a second on a fast machine, where
# /usr/bin/time's hundredths would decide the speedup), kept as a minimum.
wall() {
  local start end
  start=$(date +%s%N)
  (cd "$tmp" && "$1" -q -t "$2" -O "$tmp/threads.png" "${@:5}" "$3" > /dev/null)
  end=$(date +%s%N)
  keep_min "$4" "$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", (b - a) / 1e9 }')"
}
orig() {
  local file=$1 tag=$2
  (cd "$tmp" && /usr/bin/time -f "%U %S" -o "$tmp/time" "$original" "$file" \
      > "$tmp/$tag.orig.mtv" 2> "$tmp/orig.stats")
  keep_min "$tag.ocpu" "$(cpu_of "$tmp/time")"
  best[$tag.otests]=$(awk -F'\t+' '/^Total prim. intersection tests:/ { split($2, a, " "); print a[1] }' "$tmp/orig.stats")
}
pov() {
  local s=$1
  (cd "$tmp" && /usr/bin/time -f "%U %S" -o "$tmp/time" povray "+I$s.pov" "+O$tmp/pov.png" \
      +W512 +H512 -A +WT1 -D > "$tmp/pov.log" 2>&1) || { echo "povray failed on $s" >&2; return; }
  keep_min "$s.pcpu" "$(cpu_of "$tmp/time")"
  # "using 1 thread(s) with X CPU-seconds total" follows each phase's time line.
  read -r parse trace < <(awk '/Parse Time:|Bounding Time:/ { p = 1 } /Trace Time:/ { p = 2 }
      /CPU-seconds total/ { for (i = 1; i <= NF; ++i) if ($i == "with") v = $(i + 1);
                            if (p == 1) ps += v; else if (p == 2) tr += v; p = 0 }
      END { printf "%.3f %.3f\n", ps, tr }' "$tmp/pov.log")
  keep_min "$s.pparse" "$parse"
  keep_min "$s.ptrace" "$trace"
}

for ((round = 1; round <= rounds; ++round)); do
  for s in "${scenes[@]}"; do
    if [[ ,$modes, == *,grid,* ]]; then
      ours_and_base "$s.grid.ray" "$s.grid"
      [ $have_original == 1 ] && orig "$s.grid.ray" "$s.grid"
      [ $have_pov == 1 ] && pov "$s"
    fi
    [[ ,$modes, == *,list,* ]] && ours_and_base "$s.list.ray" "$s.list"
    if [[ ,$modes, == *,default,* ]]; then
      ours_and_base "$s.default.ray" "$s.default"
      [ $have_original == 1 ] && orig "$s.default.ray" "$s.default"
    fi
    if [[ ,$modes, == *,threads,* ]]; then
      for n in 1 2; do
        wall "$rayshade" $n "$s.grid.ray" "$s.wall$n"
        wall "$rayshade" $n "$s.grid.ray" "$s.setupwall$n" -R 1 1
        [ -n "$baseRayshade" ] && wall "$baseRayshade" $n "$s.grid.ray" "$s.basewall$n"
        [ -n "$baseRayshade" ] && wall "$baseRayshade" $n "$s.grid.ray" "$s.basesetupwall$n" -R 1 1
      done
    fi
  done
done

fidelity() {
  local tag=$1
  [ -f "$tmp/$tag.orig.mtv" ] || { echo -; return; }
  "$imgdiff" --mean 1 --max 2 --frac 2 --bright 1e9 "$tmp/$tag.ours.png" "$tmp/$tag.orig.mtv" |
      awk '{ for (i = 1; i <= NF; ++i) if ($i == "mean") { printf "%.5f", $(i + 1); exit } }'
}
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (a == "" || b == "" || b == 0) print "-"; else printf "%.2fx", a / b }'; }
num() { [ -n "${1:-}" ] && echo "$1" || echo -; }
rate() { awk -v r="$1" -v c="$2" -v s="$3" 'BEGIN { if (r == "" || c - s <= 0) print "-"; else printf "%.2fM", r / (c - s) / 1e6 }'; }

# base_columns TAG: the base build's CPU seconds, setup and our ratio to it (with -c).
base_columns() {
  [ -n "$baseRayshade" ] || return 0
  printf " | %7s %7s %7s" "$(num "${best[$1.base.cpu]:-}")" "$(num "${best[$1.base.setup]:-}")" \
      "$(ratio "${best[$1.cpu]}" "${best[$1.base.cpu]:-}")"
}
base_header() { [ -n "$baseRayshade" ] && printf " | %7s %7s %7s" base "b.setup" "vs base"; return 0; }

echo "SPD, 512x512, one thread, CPU seconds (min of $rounds interleaved round(s)); ratios are ours / theirs"
[ -n "$baseRayshade" ] && echo "base: $baseRayshade"
if [[ ,$modes, == *,grid,* ]]; then
  echo
  echo "grid files, one ray per pixel"
  printf "%-7s %7s %7s %7s | %7s %7s | %7s %7s %7s %7s | %11s %11s %9s %8s" scene ours setup render \
      orig "vs orig" "pov" "trace" "vs pov" "r/trace" "our tests" "orig tests" "rays/s" fid
  base_header; echo
  for s in "${scenes[@]}"; do
    t=$s.grid c=${best[$s.grid.cpu]} u=${best[$s.grid.setup]}
    r=$(awk -v c="$c" -v u="$u" 'BEGIN { printf "%.3f", c - u }')
    printf "%-7s %7s %7s %7s | %7s %7s | %7s %7s %7s %7s | %11s %11s %9s %8s" "$s" "$c" "$u" "$r" \
        "$(num "${best[$t.ocpu]:-}")" "$(ratio "$c" "${best[$t.ocpu]:-}")" \
        "$(num "${best[$s.pcpu]:-}")" "$(num "${best[$s.ptrace]:-}")" \
        "$(ratio "$c" "${best[$s.pcpu]:-}")" "$(ratio "$r" "${best[$s.ptrace]:-}")" \
        "$(num "${best[$t.tests]}")" "$(num "${best[$t.otests]:-}")" \
        "$(rate "${best[$t.rays]}" "$c" "$u")" "$(fidelity "$t")"
    base_columns "$t"; echo
  done
fi
if [[ ,$modes, == *,list,* ]]; then
  echo
  echo "list files (no grid), one ray per pixel"
  printf "%-7s %7s %7s %7s | %9s | %11s %9s" scene ours setup render "vs grid" "our tests" "rays/s"
  base_header; echo
  for s in "${scenes[@]}"; do
    t=$s.list c=${best[$t.cpu]} u=${best[$t.setup]}
    r=$(awk -v c="$c" -v u="$u" 'BEGIN { printf "%.3f", c - u }')
    printf "%-7s %7s %7s %7s | %9s | %11s %9s" "$s" "$c" "$u" "$r" \
        "$(ratio "$c" "${best[$s.grid.cpu]:-}")" "$(num "${best[$t.tests]}")" \
        "$(rate "${best[$t.rays]}" "$c" "$u")"
    base_columns "$t"; echo
  done
fi
if [[ ,$modes, == *,default,* ]]; then
  echo
  echo "grid files, Rayshade's default sampling (adaptive, jittered)"
  printf "%-7s %7s %7s %7s | %7s %7s | %11s %11s %9s" scene ours setup render orig "vs orig" \
      "our tests" "orig tests" "rays/s"
  base_header; echo
  for s in "${scenes[@]}"; do
    t=$s.default c=${best[$t.cpu]} u=${best[$t.setup]}
    r=$(awk -v c="$c" -v u="$u" 'BEGIN { printf "%.3f", c - u }')
    printf "%-7s %7s %7s %7s | %7s %7s | %11s %11s %9s" "$s" "$c" "$u" "$r" \
        "$(num "${best[$t.ocpu]:-}")" "$(ratio "$c" "${best[$t.ocpu]:-}")" \
        "$(num "${best[$t.tests]}")" "$(num "${best[$t.otests]:-}")" "$(rate "${best[$t.rays]}" "$c" "$u")"
    base_columns "$t"; echo
  done
fi
if [[ ,$modes, == *,threads,* ]]; then
  echo
  echo "grid files, wall seconds with one and two threads (speedup = 1 thread / 2 threads);"
  echo "setup: the same at -R 1 1 (parse, acceleration builds, one pixel); load average $(cut -d' ' -f1-3 /proc/loadavg)"
  printf "%-7s %7s %7s %7s %7s %7s %7s" scene "-t 1" "-t 2" speedup "setup1" "setup2" speedup
  [ -n "$baseRayshade" ] && printf " | %7s %7s %7s %7s %7s %7s" "base -t1" "base -t2" speedup "setup1" "setup2" speedup
  echo
  for s in "${scenes[@]}"; do
    printf "%-7s %7s %7s %7s %7s %7s %7s" "$s" "${best[$s.wall1]}" "${best[$s.wall2]}" \
        "$(ratio "${best[$s.wall1]}" "${best[$s.wall2]}")" "${best[$s.setupwall1]}" \
        "${best[$s.setupwall2]}" "$(ratio "${best[$s.setupwall1]}" "${best[$s.setupwall2]}")"
    [ -n "$baseRayshade" ] && printf " | %7s %7s %7s %7s %7s %7s" "${best[$s.basewall1]}" \
        "${best[$s.basewall2]}" "$(ratio "${best[$s.basewall1]}" "${best[$s.basewall2]}")" \
        "${best[$s.basesetupwall1]}" "${best[$s.basesetupwall2]}" \
        "$(ratio "${best[$s.basesetupwall1]}" "${best[$s.basesetupwall2]}")"
    echo
  done
fi

#!/usr/bin/env bash
# Warm frames of two builds of gl_shafts compared in one run: the table-1
# scenes (teapot spotlight, five spots on a stage, mountains, stained glass)
# at 640x480 with the defaults, each scene timed by gl_shafts_bench (no
# reference) from build A and build B in turn, the order swapped every
# round so that both see the same machine load and neither always goes
# first. Prints, per scene, the median over the rounds of each build's
# median warm frame, the median of the rounds' ratios B / A (each round's
# two runs saw about the same load), the same for the CPU time a warm frame
# took in all the process's threads (which the machine's other jobs move
# less than the wall time), and A's and B's split of their last round's
# median frame (shadow maps and light volumes, surfaces, lattice, sweep,
# read-back), as a Markdown table.
#
#   gl_shafts/ab_bench.sh --a BUILD_DIR --b BUILD_DIR [--rounds N] [--frames N]
#                         [--size W H] [--backend auto|egl|osmesa]
#                         [--scene NAME]...
#
# --scene limits the run to the named scenes of the four (teapot_spot,
# stage_5spots, mountains_sun, stained_glass), for more rounds of one.
#
# BUILD_DIR is a CMake build tree with gl_shafts/gl_shafts_bench built (a
# tree of the commit before a change, say, and one of the change).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
a='' b='' rounds=5 frames=9 w=640 h=480 backend=auto scenes=()
while [ $# -gt 0 ]; do
  case $1 in
    --a) a=$2; shift 2 ;;
    --b) b=$2; shift 2 ;;
    --rounds) rounds=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --size) w=$2 h=$3; shift 3 ;;
    --backend) backend=$2; shift 2 ;;
    --scene) scenes+=("$2"); shift 2 ;;
    -h|--help) sed -n '2,22p' "$0"; exit 0 ;;
    *) echo "ab_bench.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
for d in "$a" "$b"; do
  [ -n "$d" ] && [ -x "$d/gl_shafts/gl_shafts_bench" ] ||
    { echo "ab_bench.sh: give --a and --b, build trees with gl_shafts_bench" >&2; exit 2; }
done
echo "machine: $(nproc) CPUs, load average $(cut -d' ' -f1-3 /proc/loadavg)," \
     "$(date -u +%Y-%m-%dT%H:%MZ); $rounds rounds of $frames frames, ${w}x${h}"
echo
echo "| scene | A ms | B ms | B / A | A CPU ms | B CPU ms | B / A CPU | A: shadow / surface / lattice / sweep / read-back ms | B: the same |"
echo "|---|---:|---:|---:|---:|---:|---:|---|---|"
# One bench row's median frame (column 9, "best (median)"), CPU time a
# frame (10) and split (13), as "ms|cpu|split".
row() {
  "$1/gl_shafts/gl_shafts_bench" --size "$w" "$h" --frames "$frames" --ref-spp 0 \
    --backend "$backend" "$2" | tail -n 1 |
    awk -F'|' '{ split($9, t, /[()]/); gsub(/ /, "", t[2]); c = $10; gsub(/ /, "", c)
                 print t[2] "|" c "|" $13 }'
}
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
[ ${#scenes[@]} -gt 0 ] || scenes=(teapot_spot stage_5spots mountains_sun stained_glass)
for s in "${scenes[@]}"; do
  scene=$root/scenes/$s.json ta=() tb=() q=() ca=() cb=() qc=() sa='' sb=''
  for ((i = 0; i < rounds; i++)); do
    if ((i % 2 == 0)); then ra=$(row "$a" "$scene"); rb=$(row "$b" "$scene")
    else rb=$(row "$b" "$scene"); ra=$(row "$a" "$scene"); fi
    IFS='|' read -r ma ca1 sa <<< "$ra"
    IFS='|' read -r mb cb1 sb <<< "$rb"
    ta+=("$ma") tb+=("$mb") ca+=("$ca1") cb+=("$cb1")
    q+=("$(awk -v x="$mb" -v y="$ma" 'BEGIN { print x / y }')")
    qc+=("$(awk -v x="$cb1" -v y="$ca1" 'BEGIN { print x / y }')")
  done
  med() { printf '%s\n' "$@" | median; }
  printf '| %s | %s | %s | %.2f | %s | %s | %.2f |%s|%s|\n' "$s.json" \
    "$(med "${ta[@]}")" "$(med "${tb[@]}")" "$(med "${q[@]}")" \
    "$(med "${ca[@]}")" "$(med "${cb[@]}")" "$(med "${qc[@]}")" "$sa" "$sb"
done

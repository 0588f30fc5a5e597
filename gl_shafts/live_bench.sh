#!/usr/bin/env bash
# The live-mode benchmark: what a viewport pays for a frame after an edit,
# baked programs against live ones (gs_options.live), in-process at 640x480
# on the teapot spotlight and the five spots on a stage: first frame, warm
# frame, frames after a light move, an intensity change and a camera move
# (gl_shafts_live_bench, wall-clock and CPU time, programs built); then, with
# --instructions, the instructions of a warm frame of each kind at 320x240
# under callgrind (llvmpipe on one thread), which the machine's load does
# not move; with --disk-cache, the first frames of two sessions in turn
# with Mesa's on-disk shader cache on, in a fresh cache directory (the
# second session finds the first one's programs). Elsewhere Mesa's disk
# cache is off, so that first frames build their programs as a fresh
# install does. Prints Markdown; docs/gl_shafts.md ("Live mode") quotes it.
#
#   gl_shafts/live_bench.sh [--build DIR] [--frames N] [--instructions]
#                           [--disk-cache]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=$root/build frames=9 instructions=0 disk_cache=0
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --instructions) instructions=1; shift ;;
    --disk-cache) disk_cache=1; shift ;;
    -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
    *) echo "live_bench.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
bench=$build/gl_shafts/gl_shafts_live_bench
[ -x "$bench" ] || { echo "live_bench.sh: build first: $bench is missing" >&2; exit 2; }
export MESA_SHADER_CACHE_DISABLE=true
scenes=("$root/scenes/teapot_spot.json" "$root/scenes/stage_5spots.json")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "machine: $(nproc) CPUs, load average $(cut -d' ' -f1-3 /proc/loadavg)," \
     "$(date -u +%Y-%m-%dT%H:%MZ), commit $(git -C "$root" rev-parse --short HEAD)"
"$bench" --size 640 480 --frames "$frames" "${scenes[@]}"

if [ "$instructions" = 1 ]; then
  command -v valgrind > /dev/null || { echo "live_bench.sh: valgrind is missing" >&2; exit 2; }
  echo
  echo "Instructions of a warm frame at 320x240 (callgrind, LP_NUM_THREADS=0):"
  echo
  echo "| scene | baked | live | live / baked |"
  echo "|---|---:|---:|---:|"
  for s in "${scenes[@]}"; do
    n=()
    for mode in baked live; do
      LP_NUM_THREADS=0 valgrind --tool=callgrind --instr-atstart=no \
        --callgrind-out-file="$tmp/cg.out" "$bench" --count "$mode" --size 320 240 \
        --frames 2 "$s" 2> "$tmp/log"
      n+=("$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$tmp/log")")
    done
    awk -v s="$(basename "$s")" -v b="${n[0]}" -v l="${n[1]}" \
      'BEGIN { printf "| %s | %.1f M | %.1f M | %.2f |\n", s, b / 2e6, l / 2e6, l / b }'
  done
fi

if [ "$disk_cache" = 1 ]; then
  echo
  echo "First frames at 640x480 with Mesa's disk shader cache on, two sessions in turn"
  echo "(a fresh cache directory; columns as above):"
  echo
  echo "| scene | session | baked ms | live ms | live / baked | baked CPU ms | live CPU ms |"
  echo "|---|---|---:|---:|---:|---:|---:|"
  for s in "${scenes[@]}"; do
    for session in 1 2; do
      MESA_SHADER_CACHE_DISABLE=false MESA_SHADER_CACHE_DIR="$tmp/mesa_cache" \
        "$bench" --size 640 480 --frames 1 "$s" | grep '^| first frame' |
        awk -F'|' -v s="$(basename "$s")" -v n="$session" \
          '{ printf "| %s | %s |%s|%s|%s|%s|%s|\n", s, n, $3, $4, $5, $6, $7 }'
    done
  done
fi

# Shared by gl_shafts' benchmark scripts (sourced, after `set -euo
# pipefail` and with `root` set to the source tree): bench_setup NAME
# HELP_LINES ARGS... parses --build DIR, --size W H, --frames N and
# --ref-spp N into build, w, h, frames and spp (the caller's defaults
# stand otherwise; w and h empty: the scenes' sizes), -h prints the lines
# HELP_LINES (a sed range such as 2,15) of the script; then finds
# gl_shafts_bench (bench), makes the references' cache (cache) and prints
# the machine's line. A script with options of its own defines
# bench_option, called with the arguments left: it sets its variables,
# sets bench_shift to the number of arguments it took and returns 0, or
# returns 1 for an argument it does not know. bench_run ARGS... runs
# gl_shafts_bench with them.
bench_setup() {
  local name=$1 help=$2 script=$0
  shift 2
  while [ $# -gt 0 ]; do
    case $1 in
      --build) build=$2; shift 2 ;;
      --size) w=$2; h=$3; shift 3 ;;
      --frames) frames=$2; shift 2 ;;
      --ref-spp) spp=$2; shift 2 ;;
      -h|--help) sed -n "${help}p" "$script"; exit 0 ;;
      *)
        bench_shift=0
        if declare -F bench_option >/dev/null && bench_option "$@"; then
          shift "$bench_shift"
        else
          echo "$name: unknown argument '$1'" >&2; exit 2
        fi ;;
    esac
  done
  bench=$build/gl_shafts/gl_shafts_bench
  [ -x "$bench" ] || { echo "$name: build first: $bench is missing" >&2; exit 2; }
  cache=$build/gl_shafts_refs
  mkdir -p "$cache"
  echo "machine: $(nproc) CPUs, load average $(cut -d' ' -f1-3 /proc/loadavg)," \
       "$(date -u +%Y-%m-%dT%H:%MZ), $(git -C "$root" rev-parse --short HEAD)"
}
bench_run() {
  "$bench" ${w:+--size "$w" "$h"} --frames "$frames" --ref-spp "$spp" --cache "$cache" "$@"
}

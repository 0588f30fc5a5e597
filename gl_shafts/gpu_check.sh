#!/usr/bin/env bash
# The GPU check (issue 13 part 3): on a machine with a graphics card, does
# gl_shafts reach it through EGL, how fast is it, and does it still draw
# the right image? Builds what it needs (configuring BUILD if it never
# was, else bringing the two programs up to date), prints the
# devices EGL lists and the renderer gl_shafts gets through EGL, then
# renders the seed's four table-1 scenes (teapot spotlight, five spots on a
# stage, mountains, stained glass) at 640x480 and 1920x1080 in-process
# (gl_shafts_bench: a warm-up frame, then the best and median of the timed
# frames, the context counted apart) and compares each with a reference of
# the ray tracer's reference mode, rendered once at a modest sample count
# and kept in BUILD/gpu_check_refs (found there on later runs).
#
#   gl_shafts/gpu_check.sh [--build DIR] [--quick] [--smoke] [--frames N]
#                          [--ref-spp N] [--ref-spp-hd N] [--max-error PCT]
#
# --quick     no references at 1920x1080 (the frames are still timed)
# --smoke     160x120 only, 1 frame, 16-sample references, errors up to
#             50%: the CTest smoke run (gl_shafts.gpu_check_smoke), seconds
# --max-error an error above PCT % relative RMS (the bench's error column)
#             fails the check (default 20: the references' own noise at
#             these sample counts is up to 5%, on the stage and the
#             stained glass at 1920x1080; a broken image is far above it)
#
# Exit status: 0 when the renders ran on a hardware device and every error
# is within the bound; 3 when everything ran and passed but on a software
# rasterizer (llvmpipe: no GPU here, or EGL did not reach it); 1 when a
# render failed or an error is above the bound; 2 for bad arguments.
# On a fresh machine with an NVIDIA GPU and Debian's packages
# (tools/bootstrap.sh, plus the NVIDIA driver's EGL), it runs unattended in
# a few minutes, most of it the references (docs/gl_shafts.md, "GPU
# check").
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=$root/build frames=5 spp=256 spp_hd=64 quick=0 smoke=0 max_error=20
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --ref-spp) spp=$2; shift 2 ;;
    --ref-spp-hd) spp_hd=$2; shift 2 ;;
    --max-error) max_error=$2; shift 2 ;;
    --quick) quick=1; shift ;;
    --smoke) smoke=1; shift ;;
    -h|--help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0"; exit 0 ;;
    *) echo "gpu_check.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
start=$(date +%s)
bench=$build/gl_shafts/gl_shafts_bench probe=$build/gl_shafts/gl_shafts_gpu_probe
# Configured if it never was; built (or brought up to date) every time.
if [ ! -f "$build/CMakeCache.txt" ]; then
  echo "gpu_check: configuring $build" >&2
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null || exit 1
fi
cmake --build "$build" -j"$(nproc)" --target gl_shafts_bench gl_shafts_gpu_probe >/dev/null || {
  echo "gpu_check: FAIL: building gl_shafts_bench and gl_shafts_gpu_probe in $build" >&2
  exit 1
}

echo "## gpu_check: $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) CPUs, load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo '```'
"$probe" egl | tee "$build/gpu_check_probe.txt"
probe_rc=${PIPESTATUS[0]}
echo '```'
if [ "$probe_rc" != 0 ]; then
  echo "gpu_check: FAIL: gl_shafts gets no context through EGL" >&2
  exit 1
fi
if grep -q '^hardware: yes' "$build/gpu_check_probe.txt"; then
  hardware=1
else
  hardware=0
  if grep -q '^devices: 0 hardware' "$build/gpu_check_probe.txt"; then
    echo "gpu_check: no GPU is present (EGL lists no hardware device); checking llvmpipe through EGL"
  else
    echo "gpu_check: EGL lists a hardware device, but gl_shafts' context runs on $(sed -n 's/^renderer: //p' "$build/gpu_check_probe.txt")"
  fi
fi

scenes=()
for s in teapot_spot stage_5spots mountains_sun stained_glass; do
  scenes+=("$root/scenes/$s.json")
done
cache=$build/gpu_check_refs
mkdir -p "$cache"
if [ "$smoke" = 1 ]; then
  runs=("160 120 16") frames=1 max_error=50
else
  runs=("640 480 $spp")
  if [ "$quick" = 1 ]; then runs+=("1920 1080 0"); else runs+=("1920 1080 $spp_hd"); fi
fi
fail=0 out=$build/gpu_check_table.md
: >"$out"
for r in "${runs[@]}"; do
  set -- $r
  echo
  echo "### ${1}x$2, references at $3 samples per pixel$([ "$3" = 0 ] && echo ' (none: --quick)')"
  echo
  "$bench" --backend egl --size "$1" "$2" --frames "$frames" --ref-spp "$3" \
    --cache "$cache" "${scenes[@]}" | tee -a "$out"
  [ "${PIPESTATUS[0]}" = 0 ] || { echo "gpu_check: FAIL: a render at ${1}x$2 failed" >&2; fail=1; }
done
# The error column (relative RMS %, 14th) against the bound.
bad=$(awk -F'|' -v max="$max_error" '$2 ~ /json|[a-z]/ && $15 ~ /[0-9]/ && $15 + 0 > max { print $2 "(" $3 "): " $15 "%" }' "$out")
if [ -n "$bad" ]; then
  echo "gpu_check: FAIL: errors above $max_error %: $bad" >&2
  fail=1
fi
echo
echo "gpu_check: $(( $(date +%s) - start )) s; renderer: $(sed -n 's/^renderer: //p' "$build/gpu_check_probe.txt")"
[ "$fail" = 0 ] || exit 1
if [ "$hardware" = 0 ]; then
  echo "gpu_check: no hardware device was used (exit 3)"
  exit 3
fi
echo "gpu_check: passed on a hardware device"

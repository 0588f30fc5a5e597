#!/usr/bin/env bash
# The atmosphere in gl_shafts (issue 12 part 3): the canonical scenes
# scenes/sky_sunset.json and scenes/earth_from_space.json, timed in-process
# at 640x480 with the defaults (best and median of the warm frames, the
# process's CPU time a frame, the GL context and shader builds counted apart
# in the first frame); then their error against the converged reference at
# --err-size (the reference's cost grows with the pixels: 640x480 at 256
# samples takes most of an hour on 2 cores), at the defaults and over the
# number of sampling planes (the sky) or spheres (space). Prints Markdown
# tables (gl_shafts_bench's); docs/gl_shafts.md, "The atmosphere", quotes
# them. Runs under nice -n 10.
#
#   gl_shafts/atmo_bench.sh [--build DIR] [--frames N] [--ref-spp N]
#                           [--err-size W H] [--sweep LIST]
#
# References are kept in DIR/gl_shafts_refs, named after the scene file's
# contents, size and samples.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=$root/build frames=10 spp=256 ew=320 eh=240 sweep=4,8,16,32
bench_option() {
  case $1 in
    --err-size) ew=$2; eh=$3; bench_shift=3 ;;
    --sweep) sweep=$2; bench_shift=2 ;;
    *) return 1 ;;
  esac
}
. "$here/bench_lib.sh"
bench_setup atmo_bench.sh 2,17 "$@"
scenes=("$root/scenes/sky_sunset.json" "$root/scenes/earth_from_space.json")
echo
echo "### Speed at 640x480, defaults (planes: the sampling planes, or spheres from space; lattice and planes ms: the layers on the lattice and the full-resolution passes)"
echo
nice -n 10 "$bench" --size 640 480 --frames "$frames" --ref-spp 0 "${scenes[@]}"
echo
echo "### Error at ${ew}x${eh} against the reference at $spp samples, over the planes or spheres (--planes)"
echo
nice -n 10 "$bench" --size "$ew" "$eh" --frames 1 --ref-spp "$spp" --cache "$cache" \
  --sweep-planes "$sweep" "${scenes[@]}"

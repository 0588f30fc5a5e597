#!/usr/bin/env bash
# Height fog in gl_shafts (issue 12 part 3): scenes/valley_fog.json against
# the converged reference renderer, with gl_shafts' defaults and with the
# planes and the lattice swept, and beside it the same scene with a
# homogeneous medium of the fog's base coefficients (its "medium" without
# the type, base_height and scale_height), which shows what the fog itself
# costs. Then (--part side, at half the size) a version lit from the side,
# the sun 55 degrees from the view so that its shafts cross the valley,
# with the planes swept: its shafts cross the view, so a slab's part may
# pass from light to shadow and back (docs/gl_shafts.md, "Limits"). Timed
# in-process by
# gl_shafts_bench (first frame apart). Prints Markdown tables;
# docs/gl_shafts.md ("Height fog") quotes them.
#
#   gl_shafts/fog_bench.sh [--build DIR] [--size W H] [--frames N] [--ref-spp N]
#                          [--part all|main|side]
#
# References are kept in DIR/gl_shafts_refs, named after the scene's contents.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=$root/build w=320 h=240 frames=10 spp=1024 part=all
bench_option() {
  case $1 in
    --part) part=$2; bench_shift=2 ;;
    *) return 1 ;;
  esac
}
. "$here/bench_lib.sh"
bench_setup fog_bench.sh 2,17 "$@"
fog=$root/scenes/valley_fog.json
# The derived scenes live in a directory of their own under the build tree,
# with a copy of the heightfield (a scene names only files in its own tree).
twin_dir=$build/fog_bench
mkdir -p "$twin_dir/assets"
cp "$root/scenes/assets/valley.png" "$twin_dir/assets/"
twin=$twin_dir/valley_homogeneous.json
sed 's/"type": "height_fog", "base_height": 0, "scale_height": 2.0,//' "$fog" >"$twin"
grep -q height_fog "$twin" && { echo "fog_bench.sh: the twin kept its type" >&2; exit 1; }
run() {
  "$bench" --size "$w" "$h" --frames "$frames" --ref-spp "$spp" --cache "$cache" "$@"
}
if [ "$part" != side ]; then
  echo
  echo "### Defaults, ${w}x${h}: height fog and its homogeneous twin"
  echo
  run "$fog" "$twin"
  echo
  echo "### Planes (height fog)"
  echo
  run --sweep-planes 2,4,8,16,32 "$fog"
  echo
  echo "### xi on the lattice (the seed's method) and exact (height fog)"
  echo
  run --sweep-xi "$fog"
fi
if [ "$part" != main ]; then
  side=$twin_dir/valley_side.json
  sed -e 's/"direction": \[-0.2, -0.2, 1.0\]/"direction": [-0.8, -0.22, 0.5]/' \
      -e 's/"look_at": \[0.5, 3.2, -40\]/"look_at": [1.5, 2.6, -40]/' "$fog" >"$side"
  grep -q '0.8, -0.22' "$side" || { echo "fog_bench.sh: the side-lit version kept its sun" >&2; exit 1; }
  w=$((w / 2)) h=$((h / 2))
  echo
  echo "### Lit from the side, ${w}x${h}: planes"
  echo
  run --sweep-planes 8,32,128 "$side"
fi

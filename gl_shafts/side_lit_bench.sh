#!/usr/bin/env bash
# Shafts crossing the view within one slab (issue 12 part 3, leftover 2):
# testdata/side_comb.json, a fog box lit from the side through a comb of
# thin slats, whose shadow sheets cross every view ray several times
# between two sampling planes, against the converged reference renderer
# with the planes swept; then valley_fog.json lit from the side (as
# fog_bench.sh --part side) and mountains_sun.json, whose shafts the
# visibility sampling per shadow-map texel (plane_dir.frag's vis_step)
# must not slow much. Timed in-process by gl_shafts_bench (first frame
# apart). Prints Markdown tables; docs/gl_shafts.md ("Shafts crossing the
# view within one slab") quotes them.
#
#   gl_shafts/side_lit_bench.sh [--build DIR] [--frames N] [--ref-spp N]
#
# References are kept in DIR/gl_shafts_refs, named after the scene's contents.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=$root/build frames=5 spp=1024
. "$here/bench_lib.sh"
bench_setup side_lit_bench.sh 2,15 "$@"
echo
echo "### The comb lit from the side, 96x72: planes"
echo
bench_run --sweep-planes 4,8,32,128 "$here/testdata/side_comb.json"
# The valley lit from the side, in a directory of its own with a copy of
# the heightfield (a scene names only files in its own tree).
dir=$build/side_lit_bench
mkdir -p "$dir/assets"
cp "$root/scenes/assets/valley.png" "$dir/assets/"
side=$dir/valley_side.json
sed -e 's/"direction": \[-0.2, -0.2, 1.0\]/"direction": [-0.8, -0.22, 0.5]/' \
    -e 's/"look_at": \[0.5, 3.2, -40\]/"look_at": [1.5, 2.6, -40]/' \
    "$root/scenes/valley_fog.json" >"$side"
grep -q '0.8, -0.22' "$side" || { echo "side_lit_bench.sh: the side-lit valley kept its sun" >&2; exit 1; }
echo
echo "### valley_fog lit from the side and mountains_sun, 160x120, default planes"
echo
bench_run --size 160 120 "$side" "$root/scenes/mountains_sun.json"

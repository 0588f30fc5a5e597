#!/usr/bin/env bash
# Shapes and lights in the atmosphere (issue 12 part 3 leftovers):
# testdata/atmo_casters.json (pillars and a ball casting the sun's shadows
# into the air at sunset) and testdata/atmo_lamps.json (a point light and
# a spot at night) against the converged reference renderer with the
# sampling planes (and the lights' angle steps) swept, and beside them the
# casters' scene without its shapes, which shows what the shapes cost.
# Timed in-process by gl_shafts_bench (first frame apart). Prints Markdown
# tables; docs/gl_shafts.md ("Shapes and lights in the atmosphere") quotes
# them.
#
#   gl_shafts/atmo_shapes_bench.sh [--build DIR] [--size W H] [--frames N]
#                                  [--ref-spp N]
#
# References are kept in DIR/gl_shafts_refs, named after the scene's contents.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=$root/build w=96 h=72 frames=5 spp=1024
. "$here/bench_lib.sh"
bench_setup atmo_shapes_bench.sh 2,16 "$@"
dir=$build/atmo_shapes_bench
mkdir -p "$dir"
casters=$here/testdata/atmo_casters.json lamps=$here/testdata/atmo_lamps.json
bare=$dir/atmo_casters_bare.json
python3 -c 'import json, sys
s = json.load(open(sys.argv[1])); s["shapes"] = []; s["materials"] = {}
json.dump(s, open(sys.argv[2], "w"), indent=1)' "$casters" "$bare"
echo
echo "### ${w}x${h}, defaults: the casters, the same air without them, the lamps"
echo
bench_run "$casters" "$bare" "$lamps"
echo
echo "### Planes (the casters) and angle steps (the lamps)"
echo
bench_run --sweep-planes 4,8,16,32 "$casters" "$lamps"

#!/usr/bin/env bash
# The gl_shafts benchmark: the seed's table-1 scenes (teapot spotlight, five
# spots on a stage, mountains, stained glass) at 640x480 with the default
# settings, timed in-process (the GL context and shader compilation counted
# apart, in the first frame) against the converged reference renderer; then,
# with --sweeps, how error and time move with the planes and the lattice
# (the seed's figures 5 and 6) and with the sub-samples. With --backends,
# instead: the defaults once per GL backend (EGL, OSMesa), scene by scene,
# each pair in turn in the other order, so that both see the same machine
# load and neither always starts cold. Prints Markdown
# tables; docs/gl_shafts.md quotes them.
#
#   gl_shafts/bench.sh [--build DIR] [--frames N] [--ref-spp N] [--sweeps]
#                      [--backend auto|egl|osmesa] [--backends]
#
# References are rendered once (about a minute each at 512 samples) and
# kept in DIR/gl_shafts_refs, named after the scene file's contents.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=$root/build w=640 h=480 frames=10 spp=512 sweeps=0 backend=auto backends=0
bench_option() {
  case $1 in
    --sweeps) sweeps=1; bench_shift=1 ;;
    --backend) backend=$2; bench_shift=2 ;;
    --backends) backends=1; bench_shift=1 ;;
    *) return 1 ;;
  esac
}
. "$here/bench_lib.sh"
bench_setup bench.sh 2,16 "$@"
scenes=()
for s in teapot_spot stage_5spots mountains_sun stained_glass; do
  scenes+=("$root/scenes/$s.json")
done
run() {
  "$bench" --size "$w" "$h" --frames "$frames" --ref-spp "$spp" --cache "$cache" \
    --backend "$backend" "$@"
}

if [ "$backends" = 1 ]; then
  echo
  echo "### Defaults, 640x480, per backend"
  echo
  header=1 order="egl osmesa"
  for s in "${scenes[@]}"; do
    for backend in $order; do
      if [ $header = 1 ]; then run "$s"; header=0; else run "$s" | tail -n +3; fi
    done
    [ "$order" = "egl osmesa" ] && order="osmesa egl" || order="egl osmesa"
  done
  exit 0
fi
echo
echo "### Defaults, 640x480"
echo
run "${scenes[@]}"
[ "$sweeps" = 1 ] || exit 0

teapot=$root/scenes/teapot_spot.json
echo
echo "### Planes (figure 5: lattice 40x40), teapot spotlight"
echo
run --lattice 40 40 --sweep-planes 15,30,75,150 --sweep-xi "$teapot"
echo
echo "### Lattice (figure 6: 75 planes), teapot spotlight"
echo
run --planes 75 --xi lattice --sweep-lattice 5,20,80 "$teapot"
echo
echo "### Sub-samples: degrees a sample spans at a point or spot light"
echo
run --sub-angle 16 "$teapot" "$root/scenes/stage_5spots.json"
for a in 8 4 2 1; do
  run --sub-angle "$a" "$teapot" "$root/scenes/stage_5spots.json" | tail -n +3
done
echo
echo "### Sub-samples: light-map texels (gobo or window) a sample spans"
echo
run --sub-texels 8 "$root/scenes/stage_5spots.json" "$root/scenes/stained_glass.json"
for t in 4 2 1; do
  run --sub-texels "$t" "$root/scenes/stage_5spots.json" "$root/scenes/stained_glass.json" | tail -n +3
done
echo
echo "### Planes for directional lights (defaults otherwise)"
echo
run --sweep-planes 4,8,16,32 "$root/scenes/mountains_sun.json" "$root/scenes/stained_glass.json"
